//! A static marker seen in a flat mirror moving uniformly (the
//! `reflection` kind): where the reflection of the marker's straight edge
//! crosses an image row, and the reflected light's Doppler factor.
//!
//! Expected from Einstein's law for a moving mirror ([`crate::oracle::mirror`]):
//! each line of sight is followed back to the mirror's plane on the camera's
//! past light cone, reflected by the law, and on to the marker's plane; the
//! expected column is where that path crosses the edge's line. Measured:
//! the edge is found in the rows about the read row by the area method and
//! fitted against the row, read at the row with the fit's prediction error;
//! the factor is the temperature ratio of the blackbody whose chromaticity
//! the pixel shows (tolerance from its 8-bit quantisation).

use super::doppler::{quantisation, ColourScan};
use crate::check::probe::Effort;
use crate::check::row::{Reading, Unit};
use crate::check::traced_edge::{Edge, EdgeTrace};
use crate::fixture::checks::{view_size, ReflectionRead, ReflectionSpec, ViewSpec};
use crate::measure::colorimetry::Blackbody;
use crate::measure::{self, Pinhole, Scan};
use crate::observer::{background, is_background, motion_of, Observer};
use crate::oracle::mirror::{bounce, Bounce, Marker, MovingMirror};
use glam::DVec3;
use renderer::{Shape, Spectrum, Window};

/// A row's reading, its expectation and unit, and the lab direction to mark.
type Found = ((Reading, f64, Unit), DVec3);

/// The mirror, the marker and the marker's triangles in the lab, read from
/// the described fixture.
struct Optics {
    mirror: MovingMirror,
    marker: Marker,
    triangles: Vec<[DVec3; 3]>,
}

fn mesh_corners(setup: &Observer, name: &str) -> Result<Vec<[DVec3; 3]>, String> {
    let f = setup.fixture;
    let Shape::Mesh(mesh) = &f.object(name)?.shape else {
        return Err(format!("{name:?} is not a mesh"));
    };
    let motion = motion_of(f, name, setup.model)?;
    let lab = |p: DVec3| motion.point(p).at(motion.start.t);
    Ok((0..mesh.triangles.len())
        .map(|t| mesh.corners(t).map(lab))
        .collect())
}

fn unit_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    (b - a).cross(c - a).normalize()
}

impl Optics {
    fn of(setup: &Observer, r: &ReflectionSpec) -> Result<Optics, String> {
        let f = setup.fixture;
        let mirror_motion = motion_of(f, &r.mirror, setup.model)?;
        let mirror_corners = mesh_corners(setup, &r.mirror)?;
        let triangles = mesh_corners(setup, &r.marker)?;
        let marker_motion = motion_of(f, &r.marker, setup.model)?;
        let [a, b] = r
            .edge
            .map(|p| marker_motion.point(p).at(marker_motion.start.t));
        Ok(Optics {
            mirror: MovingMirror {
                t0: mirror_motion.start.t,
                point: mirror_corners[0][0],
                normal: unit_normal(mirror_corners[0]),
                velocity: mirror_motion.velocity,
            },
            marker: Marker {
                a,
                b,
                normal: unit_normal(triangles[0]),
            },
            triangles,
        })
    }

    fn bounce(&self, setup: &Observer, camera: &Pinhole, (px, py): (f64, f64)) -> Option<Bounce> {
        let d = camera.direction(px, py);
        bounce(
            &self.mirror,
            &self.marker,
            setup.camera_t,
            setup.camera_x(),
            d,
        )
    }

    /// Whether a point of the marker's plane lies on one of its triangles.
    fn on_marker(&self, p: DVec3) -> bool {
        self.triangles.iter().any(|&[a, b, c]| {
            let n = (b - a).cross(c - a);
            let inside = |u: DVec3, v: DVec3| (v - u).cross(p - u).dot(n) >= 0.0;
            inside(a, b) && inside(b, c) && inside(c, a)
        })
    }
}

/// Measures the reflection check `r` in `view`: rendered with `measuring`,
/// expected from `described`.
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    r: &ReflectionSpec,
    view: &ViewSpec,
    effort: &Effort,
) -> Result<Found, String> {
    let optics = Optics::of(described, r)?;
    match r.read {
        ReflectionRead::Column => column(measuring, described, &optics, r, view, effort),
        ReflectionRead::Doppler => doppler(measuring, described, &optics, r, view),
    }
}

/// The column where the oracle's path crosses the edge's line on the row:
/// the one sign change of the side along the row, refined by bisection.
fn expected_column(
    optics: &Optics,
    setup: &Observer,
    camera: &Pinhole,
    (w, yc): (u32, f64),
) -> Result<f64, String> {
    let side = |px: f64| optics.bounce(setup, camera, (px, yc)).map(|b| b.side);
    let steps = 4 * w;
    let at = |i: u32| f64::from(i) / 4.0;
    let changes: Vec<u32> = (0..steps)
        .filter(|&i| matches!((side(at(i)), side(at(i + 1))), (Some(a), Some(b)) if (a < 0.0) != (b < 0.0)))
        .collect();
    let &[i] = changes.as_slice() else {
        return Err(format!(
            "the oracle sees the marker's reflected edge cross row {} {} times (it must cross once)",
            yc - 0.5,
            changes.len()
        ));
    };
    let (mut lo, mut hi) = (at(i), at(i + 1));
    let below = side(lo).unwrap_or(0.0) < 0.0;
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        match side(mid) {
            Some(s) if (s < 0.0) == below => lo = mid,
            _ => hi = mid,
        }
    }
    Ok(0.5 * (lo + hi))
}

fn column(
    measuring: &Observer,
    described: &Observer,
    optics: &Optics,
    r: &ReflectionSpec,
    view: &ViewSpec,
    effort: &Effort,
) -> Result<Found, String> {
    let size = view_size(&measuring.fixture.spec, view);
    let spp = view.spp.unwrap_or(effort.spp);
    let depth = measuring.fixture.spec.image.max_depth;
    let keep = [r.mirror.as_str(), r.marker.as_str()];
    // Only the band of rows the edge is traced along is rendered.
    let band = (size.1 / 20).max(4);
    let rows = r.row.saturating_sub(band)..=(r.row + band).min(size.1 - 1);
    let window = Window {
        x: 0,
        y: *rows.start(),
        width: size.0,
        height: rows.end() + 1 - rows.start(),
    };
    let (img, camera) = measuring.measuring_window(&keep, size, (spp, depth), window)?;
    let yc = f64::from(r.row) + 0.5;
    let expected = expected_column(optics, described, &camera, (size.0, yc))?;
    // Scan from the side of the edge where the mirror shows no marker.
    let bg = background(measuring.fixture);
    let sees_marker = |px: f64| {
        optics
            .bounce(described, &camera, (px, yc))
            .is_some_and(|b| optics.on_marker(b.on_marker))
    };
    let from_left = sees_marker(expected + 1.0) && !sees_marker(expected - 1.0);
    let (from, step) = if from_left {
        (0, 1)
    } else {
        (i64::from(size.0) - 1, -1)
    };
    let points = rows
        .filter_map(|y| {
            let scan = Scan {
                horizontal: true,
                at: y - window.y,
            };
            let u = measure::edge(&img, scan, from, step, |c| is_background(c, bg))?;
            Some((f64::from(y) + 0.5, u))
        })
        .collect();
    let trace = EdgeTrace {
        points,
        footprint: 1.0,
    };
    let fitted = Edge::fit(&trace, 2, &Effort { probe: 0, spp }).map_err(|e| {
        format!(
            "the reflected edge is not visible in view {:?}: {e}",
            r.view
        )
    })?;
    let mark = camera.direction(expected, yc);
    Ok(((fitted.at(yc), expected, Unit::Pixels), mark))
}

fn doppler(
    measuring: &Observer,
    described: &Observer,
    optics: &Optics,
    r: &ReflectionSpec,
    view: &ViewSpec,
) -> Result<Found, String> {
    let marker = described.fixture.object(&r.marker)?;
    let Some(Spectrum::Blackbody { kelvin, scale }) = marker.material.emission else {
        return Err(format!("{:?} does not glow as a blackbody", r.marker));
    };
    let source = Blackbody { kelvin, scale };
    let mut shifted = measuring.fixture.clone();
    (shifted.spec.image.doppler, shifted.spec.image.searchlight) = (true, false);
    let setup = Observer {
        fixture: &shifted,
        ..*measuring
    };
    let size = view_size(&measuring.fixture.spec, view);
    let depth = measuring.fixture.spec.image.max_depth;
    let keep = [r.mirror.as_str(), r.marker.as_str()];
    let column = r.column.unwrap_or(0);
    // Only the pixel read is rendered.
    let only = Window {
        x: column,
        y: r.row,
        width: 1,
        height: 1,
    };
    let (img, camera) = setup.measuring_window(&keep, size, (1, depth), only)?;
    let centre = (f64::from(column) + 0.5, f64::from(r.row) + 0.5);
    let path = optics
        .bounce(described, &camera, centre)
        .filter(|b| optics.on_marker(b.on_marker))
        .ok_or_else(|| {
            format!(
                "pixel ({column}, {}) does not see the marker by way of the mirror",
                r.row
            )
        })?;
    let rgb = measure::color(&img, 0, 0);
    let range = (0.2, 5.0);
    let scan = ColourScan::new(&source, range);
    let from_colour = |c: DVec3| scan.factor(c);
    let reading = Reading {
        value: from_colour(rgb).unwrap_or(f64::NAN),
        tolerance: quantisation(rgb, from_colour),
    };
    Ok((
        (reading, path.factor, Unit::Factor),
        camera.direction(centre.0, centre.1),
    ))
}
