//! The cube's silhouette on the horizon, measured: a coarse wide strip
//! finds each edge, a narrow probe aimed there traces it over rows on the
//! sphere of directions (elevation against azimuth, in the observer's own
//! frame), and the fit is read at elevation 0.

use super::cases::{azimuth_deg, CUBE, NAME};
use crate::check::probe::{Effort, Probe};
use crate::check::row::Reading;
use crate::check::traced_edge::{Edge, EdgeTrace, OnPlane, ProbeImage};
use crate::measure::{Pinhole, Plane};
use crate::observer::{background, is_background, Observer};
use glam::DVec3;

/// Measures the silhouette edge on the horizon near azimuth `near_deg`:
/// a narrow probe aimed there, the edge traced over rows and fitted
/// against elevation, read at elevation 0.
fn measure_edge(
    setup: &Observer,
    near_deg: f64,
    right: bool,
    effort: &Effort,
) -> Result<Reading, String> {
    let a = near_deg.to_radians();
    let look = DVec3::new(libm::sin(a), 0.0, -libm::cos(a));
    // A strip 3 degrees wide and 0.6 tall across the horizon, half the
    // probe's width: the angle targets (0.05 deg) are met ~100x over.
    let mut probe = ProbeImage::render_lazy(
        setup,
        &Probe {
            keep: &[CUBE],
            look_at: look,
            hfov_deg: 3.0,
            size: (effort.probe / 2, effort.probe / 10),
            spp: effort.spp,
        },
    )?;
    let sweep = if right {
        probe.sweep_leftwards()
    } else {
        probe.sweep_rightwards()
    };
    // Angles are the observer's: lines of sight in the camera's own frame
    // (the same as the lab's when the camera is at rest).
    probe.camera = probe.camera.still();
    // On the unit sphere of directions: elevation (deg) against azimuth (deg).
    let sphere = OnPlane {
        plane: Plane::z(-1.0),
        coords: |p: DVec3| (p.y.atan2(p.x.hypot(p.z)).to_degrees(), azimuth_deg(p)),
        range: (-0.25, 0.25),
        degree: 2,
    };
    let trace = probe
        .trace(&sphere, sweep, probe.background())
        .map_err(|e| format!("{NAME}: edge near {near_deg:.2} deg: {e}"))?;
    let trace = EdgeTrace {
        footprint: measure_angular(&probe.camera),
        ..trace
    };
    Ok(Edge::fit(&trace, sphere.degree, effort)
        .map_err(|e| format!("{NAME}: edge near {near_deg:.2} deg: {e}"))?
        .at(0.0))
}

/// Angular size of a probe pixel at its centre, degrees.
fn measure_angular(camera: &Pinhole) -> f64 {
    let (cx, cy) = (
        f64::from(camera.width) / 2.0,
        f64::from(camera.height) / 2.0,
    );
    camera.angular_footprint(cx, cy, true).to_degrees()
}

/// Rough azimuths (left, right) of the silhouette on the horizon, from a
/// wide render.
fn coarse_edges(setup: &Observer) -> Result<(f64, f64), String> {
    // A wide strip across the horizon first; where the cube reaches its
    // border (beyond +-85 degrees), a second strip turned towards that side.
    let (l, r) = coarse_strip(setup, 0.0, 170.0)?;
    let l = if l.1 {
        coarse_strip(setup, -60.0, 60.0)?.0 .0
    } else {
        l.0
    };
    let r = if r.1 {
        coarse_strip(setup, 60.0, 60.0)?.1 .0
    } else {
        r.0
    };
    Ok((l, r))
}

/// A rough edge azimuth (degrees), and whether it lies on the probe's border.
type CoarseEdge = (f64, bool);

/// The azimuths of the leftmost and rightmost cube pixels on the horizon of
/// a strip centred on azimuth `centre_deg`, each with whether it lies on the
/// strip's border.
fn coarse_strip(
    setup: &Observer,
    centre_deg: f64,
    hfov_deg: f64,
) -> Result<(CoarseEdge, CoarseEdge), String> {
    let a = centre_deg.to_radians();
    let (img, camera) = setup.probe(&Probe {
        keep: &[CUBE],
        look_at: DVec3::new(libm::sin(a), 0.0, -libm::cos(a)),
        hfov_deg,
        size: (1441, 3),
        spp: 1,
    })?;
    let bg = background(setup.fixture);
    let row = img.height() / 2;
    let xs: Vec<u32> = (0..img.width())
        .filter(|x| !is_background(crate::measure::color(&img, *x, row), bg))
        .collect();
    let (Some(&l), Some(&r)) = (xs.first(), xs.last()) else {
        return Err(format!("{NAME}: the cube is not on the horizon"));
    };
    let camera = camera.still();
    let az = |x: f64| azimuth_deg(camera.direction(x, f64::from(row) + 0.5));
    Ok((
        (az(f64::from(l)), l == 0),
        (az(f64::from(r) + 1.0), r + 1 == img.width()),
    ))
}

/// Measures both silhouette edges of a setup on the horizon.
pub(super) fn measure_edges(
    setup: &Observer,
    effort: &Effort,
) -> Result<(Reading, Reading), String> {
    let (coarse_l, coarse_r) = coarse_edges(setup)?;
    Ok((
        measure_edge(setup, coarse_l, false, effort)?,
        measure_edge(setup, coarse_r, true, effort)?,
    ))
}
