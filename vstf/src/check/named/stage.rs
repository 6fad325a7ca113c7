//! The stage (paper section 4, Figure 9): a static grid of bars 1/20 l.unit
//! wide on 1 l.unit centres, seen from (0, 9, 15). Nothing moves, so this
//! checks the measurement chain itself: edges fitted in the image and mapped
//! through the camera model onto the stage plane must land where the
//! fixture puts the bars.
//!
//! The green z axis bar (x = 0) is seen with both side faces hidden (the
//! camera is at x = 0), so both edges of its top face are measured; of the
//! bars at x = 1 and 2 only the right edges (the left side faces are in view).

use crate::check::findings::CheckOutcome;
use crate::check::probe::{Effort, Probe};
use crate::check::row::{difference, Quantity, Reading, Unit};
use crate::check::traced_edge::{OnPlane, ProbeImage, Sweep};
use crate::fixture::{Fixture, MeshSpec};
use crate::measure::{Pixels, Plane};
use crate::observer::{fixture_model, Observer};
use crate::run::LazyImage;
use glam::DVec3;
use std::sync::Arc;

const NAME: &str = "stage";

/// What the stage check measures, as the fixture declares it: the objects
/// holding the axis bars and the grid bars, and the depth on the stage
/// around which edges are measured (between two bars across, e.g. 2.5).
/// Probes are 2:1 strips across it: only depths within 0.35 of it are used.
pub(super) struct Bars<'a> {
    /// The object holding the x and z axis bars.
    pub axes: &'a str,
    /// The object holding the grid bars.
    pub grid: &'a str,
    /// The depth measured at, l.units.
    pub depth: f64,
}

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

/// The stage's measurements: the axis bar's centre and width, the right
/// edges of the bars x = 1 and 2 and their spacing, against the fixture's
/// mesh (the paper: bars 1/20 wide on 1 l.unit centres).
pub(super) fn run(f: &Fixture, bars: &Bars, effort: &Effort) -> Result<CheckOutcome, String> {
    let setup = Observer {
        fixture: f,
        model: fixture_model(f),
        camera_t: f.spec.camera.t,
    };
    let (ax0, ax1, top) = bar_along_z(f, bars.axes, 0.0)?;
    let (left, right) = axis_bar_edges(&setup, bars, top, effort)?;
    let [one, two] = grid_bar_right_edges(&setup, bars, top, effort)?;
    let (one_x, two_x) = (
        bar_along_z(f, bars.grid, 1.0)?.1,
        bar_along_z(f, bars.grid, 2.0)?.1,
    );
    let quantities = vec![
        Quantity {
            name: "z axis bar centre (x)".into(),
            measured: Reading {
                value: (left.value + right.value) / 2.0,
                tolerance: left.tolerance.hypot(right.tolerance) / 2.0,
            },
            expected: (ax0 + ax1) / 2.0,
            paper: Some(0.0),
            unit: Unit::LUnits,
            error: None,
        },
        Quantity {
            name: "z axis bar width".into(),
            measured: difference(&right, &left),
            expected: ax1 - ax0,
            paper: Some(1.0 / 20.0),
            unit: Unit::LUnits,
            error: None,
        },
        Quantity {
            name: "bar x = 1 right edge (x)".into(),
            measured: one,
            expected: one_x,
            paper: None,
            unit: Unit::LUnits,
            error: None,
        },
        Quantity {
            name: "bar x = 2 right edge (x)".into(),
            measured: two,
            expected: two_x,
            paper: None,
            unit: Unit::LUnits,
            error: None,
        },
        Quantity {
            name: "grid spacing (bar 1 to bar 2)".into(),
            measured: difference(&two, &one),
            expected: two_x - one_x,
            paper: Some(1.0),
            unit: Unit::LUnits,
            error: None,
        },
    ];
    let cam = setup.camera_x();
    let marks: Vec<DVec3> = [-6.0, -3.0, 0.0, 3.0, 6.0]
        .iter()
        .flat_map(|&x| [-6.0, 0.0, 6.0].map(|z| (DVec3::new(x, top, z) - cam).normalize()))
        .collect();
    Ok(CheckOutcome {
        views: vec![setup.full_view("view", &marks)?],
        quantities,
    })
}

/// Edges on the stage's top plane y = `top`, as (depth, x), within 0.35
/// of `depth`, fitted by straight lines.
fn on_stage(top: f64, depth: f64) -> OnPlane<impl Fn(DVec3) -> (f64, f64)> {
    OnPlane {
        plane: Plane::y(top),
        coords: |p: DVec3| (p.z, p.x),
        range: (depth - 0.35, depth + 0.35),
        degree: 1,
    }
}

/// A 2:1 strip probe of the objects `keep`, looking at `look_at` with
/// horizontal field of view `hfov_deg`.
fn strip(
    setup: &Observer,
    keep: &[&str],
    look_at: DVec3,
    hfov_deg: f64,
    effort: &Effort,
) -> Result<ProbeImage<Arc<LazyImage>>, String> {
    ProbeImage::render_lazy(
        setup,
        &Probe {
            keep,
            look_at,
            hfov_deg,
            size: (effort.probe, effort.probe / 2),
            spp: effort.spp,
        },
    )
}

/// Both edges of the top face of the z axis bar, alone in a narrow probe,
/// at the measured depth.
fn axis_bar_edges(
    setup: &Observer,
    bars: &Bars,
    top: f64,
    effort: &Effort,
) -> Result<(Reading, Reading), String> {
    let z = bars.depth;
    let fail = |what: &str, e: String| format!("{NAME}: {what}: {e}");
    let probe = strip(setup, &[bars.axes], DVec3::new(0.0, top, z), 4.0, effort)?;
    let stage = on_stage(top, z);
    let left = probe
        .fit(&stage, probe.sweep_rightwards(), probe.background(), effort)
        .map_err(|e| fail("axis bar left edge", e))?
        .at(z);
    let right = probe
        .fit(&stage, probe.sweep_leftwards(), probe.background(), effort)
        .map_err(|e| fail("axis bar right edge", e))?
        .at(z);
    Ok((left, right))
}

/// The right edges of the grid bars x = 1 and 2 at the measured depth,
/// each scanned leftwards from midway to the next bar.
fn grid_bar_right_edges(
    setup: &Observer,
    bars: &Bars,
    top: f64,
    effort: &Effort,
) -> Result<[Reading; 2], String> {
    let z = bars.depth;
    let cam = setup.camera_x();
    let probe = strip(setup, &[bars.grid], DVec3::new(1.5, top, z), 5.0, effort)?;
    let stage = on_stage(top, z);
    let right_edge = |k: f64| -> Result<Reading, String> {
        let from = (probe
            .camera
            .pixel_of(DVec3::new(k + 0.5, top, z) - cam)
            .ok_or("bar out of view")?
            .0
            .floor() as i64)
            .clamp(0, i64::from(probe.img.dimensions().0) - 1);
        Ok(probe
            .fit(&stage, Sweep { from, step: -1 }, probe.background(), effort)
            .map_err(|e| format!("{NAME}: bar x = {k}: {e}"))?
            .at(z))
    };
    Ok([right_edge(1.0)?, right_edge(2.0)?])
}
