//! The stage (paper section 4, Figure 9): a static grid of bars 1/20 l.unit
//! wide on 1 l.unit centres, seen from (0, 9, 15). Nothing moves, so this
//! checks the measurement chain itself: edges fitted in the image and mapped
//! through the camera model onto the stage plane must land where the
//! fixture puts the bars.
//!
//! The green z axis bar (x = 0) is seen with both side faces hidden (the
//! camera is at x = 0), so both edges of its top face are measured; of the
//! bars at x = 1 and 2 only the right edges (the left side faces are in view).

use super::{
    background, difference, is_background, trace_rows, Edge, Effort, FixtureReport, Reading, Row,
    Setup,
};
use crate::fixture::{Fixture, MeshSpec, Overrides};
use crate::measure::{edge, Plane};
use glam::DVec3;

const NAME: &str = "stage";
const AXES: &str = "x and z axis bars";
const GRID: &str = "grid bars";
/// Depth on the stage around which edges are measured, between the bars z = 2 and z = 3.
/// Probes are 2:1 strips across it: only depths within 0.35 of it are used.
const Z: f64 = 2.5;

/// The x extent and top height of the bar of `object` that runs along z
/// across x = `x`, from the fixture's mesh.
fn bar_along_z(f: &Fixture, object: &str, x: f64) -> Result<(f64, f64, f64), String> {
    let spec = f
        .spec
        .objects
        .iter()
        .find(|o| o.name == object)
        .ok_or_else(|| format!("{NAME}: no object {object:?}"))?;
    let MeshSpec::Group(parts) = &spec.mesh else {
        return Err(format!("{NAME}: {object} is not a group of bars"));
    };
    parts
        .iter()
        .find_map(|p| match p {
            MeshSpec::Cuboid { min, max } if min.x <= x && x <= max.x && max.z - min.z > 1.0 => {
                Some((min.x, max.x, max.y))
            }
            _ => None,
        })
        .ok_or_else(|| format!("{NAME}: {object} has no bar along z at x = {x}"))
}

pub fn run(effort: &Effort) -> Result<FixtureReport, String> {
    let f = Fixture::load(NAME).map_err(|e| e.to_string())?;
    let model = f
        .model(&Overrides::default())
        .map_err(|(p, m)| format!("{p}: {m}"))?;
    let setup = Setup {
        fixture: &f,
        model,
        camera_t: f.spec.camera.t,
    };
    let cam = setup.camera_x();
    let bg = background(&f);
    let (ax0, ax1, top) = bar_along_z(&f, AXES, 0.0)?;
    let stage = Plane::y(top);
    let local = |p: DVec3| (p.z, p.x);
    let depths = (Z - 0.35, Z + 0.35);
    let fail = |what: &str, e: String| format!("{NAME}: {what}: {e}");

    // The axis bar, alone, in a narrow probe.
    let (img, camera) = setup.probe(
        &[AXES],
        DVec3::new(0.0, top, Z),
        4.0,
        effort.probe,
        effort.probe / 2,
        effort.spp,
    )?;
    let w = i64::from(img.width());
    let left = trace_rows(
        &img,
        &camera,
        stage,
        |s| edge(&img, s, 0, 1, |c| is_background(c, bg)),
        local,
        depths,
    );
    let right = trace_rows(
        &img,
        &camera,
        stage,
        |s| edge(&img, s, w - 1, -1, |c| is_background(c, bg)),
        local,
        depths,
    );
    let left = Edge::fit(&left, 1, effort)
        .map_err(|e| fail("axis bar left edge", e))?
        .at(Z);
    let right = Edge::fit(&right, 1, effort)
        .map_err(|e| fail("axis bar right edge", e))?
        .at(Z);
    let centre = Reading {
        value: (left.value + right.value) / 2.0,
        tolerance: left.tolerance.hypot(right.tolerance) / 2.0,
    };
    let width = difference(&right, &left);

    // Bars x = 1 and 2: their right edges, scanning left from midway to the next bar.
    let (img, camera) = setup.probe(
        &[GRID],
        DVec3::new(1.5, top, Z),
        5.0,
        effort.probe,
        effort.probe / 2,
        effort.spp,
    )?;
    let mut right_edges = Vec::new();
    for k in [1.0, 2.0] {
        let from = (camera
            .pixel_of(DVec3::new(k + 0.5, top, Z) - cam)
            .ok_or("bar out of view")?
            .0
            .floor() as i64)
            .clamp(0, i64::from(img.width()) - 1);
        let trace = trace_rows(
            &img,
            &camera,
            stage,
            |s| edge(&img, s, from, -1, |c| is_background(c, bg)),
            local,
            depths,
        );
        let reading = Edge::fit(&trace, 1, effort)
            .map_err(|e| fail(&format!("bar x = {k}"), e))?
            .at(Z);
        right_edges.push((k, reading, bar_along_z(&f, GRID, k)?.1));
    }
    let spacing = difference(&right_edges[1].1, &right_edges[0].1);

    let row = |q: &str, m: &Reading, e: f64, paper: Option<f64>| {
        Row::new(NAME, q, m.value, e, paper, m.tolerance, "l.units")
    };
    let mut rows = vec![
        row(
            "z axis bar centre (x)",
            &centre,
            (ax0 + ax1) / 2.0,
            Some(0.0),
        ),
        row("z axis bar width", &width, ax1 - ax0, Some(1.0 / 20.0)),
    ];
    for (k, reading, expected) in &right_edges {
        rows.push(row(
            &format!("bar x = {k} right edge (x)"),
            reading,
            *expected,
            None,
        ));
    }
    rows.push(row(
        "grid spacing (bar 1 to bar 2)",
        &spacing,
        right_edges[1].2 - right_edges[0].2,
        Some(1.0),
    ));
    let marks: Vec<DVec3> = [-6.0, -3.0, 0.0, 3.0, 6.0]
        .iter()
        .flat_map(|&x| [-6.0, 0.0, 6.0].map(|z| (DVec3::new(x, top, z) - cam).normalize()))
        .collect();
    let views = vec![setup.full_view("view", &marks)?];
    Ok(FixtureReport::new(NAME, &f.spec.description, views, rows))
}
