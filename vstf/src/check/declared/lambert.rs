//! The Lambert cosine of a lit, moving matte surface, in the surface's own
//! frame (the `lambert` kind; docs/physics.md, "Shading in the surface's
//! frame").
//!
//! Measured: the centre pixel of a probe aimed where the point is seen
//! (odd-sized, so that the pixel's centre is the point's line of sight),
//! rendered without colour effects or shadows; the documented local term
//! c = albedo (ambient + L diffuse cos) (L the lamp's colour) is inverted
//! for cos in the channel where albedo L is largest, with half an 8-bit
//! step as the tolerance. Expected: cos = n'.l', with l' the direction
//! towards the lamp in the surface's frame, aberrated from the lab
//! direction at the emission event (relativistically for a V_obj under the
//! Lorentz transform, else by Galilean addition; not at all with infinitely
//! fast light), and n' the mesh's rest-frame normal turned towards the
//! viewer there (the side the light towards the camera leaves in the
//! surface's frame, which a fast surface can show even where the lab would
//! call it hidden); 0 where the lamp is behind the surface.

use crate::check::path::BodyPath;
use crate::check::probe::Probe;
use crate::check::row::{Reading, Unit};
use crate::fixture::checks::LambertSpec;
use crate::measure;
use crate::observer::Observer;
use crate::oracle::{aberrate_galilean, aberrate_lorentz};
use glam::DVec3;
use renderer::{LightSpeed, ObjectKind, Shape};

use super::doppler::{POINT_PROBE as PROBE, POINT_PROBE_FOV as PROBE_FOV};

/// A row's reading, its expectation and unit, and the lab direction to mark.
type Found = ((Reading, f64, Unit), DVec3);

/// The rest-frame unit normal of the triangle of `mesh` holding `p`.
fn rest_normal(shape: &Shape, p: DVec3) -> Option<DVec3> {
    let Shape::Mesh(mesh) = shape else {
        return None;
    };
    (0..mesh.triangles.len()).find_map(|t| {
        let [a, b, c] = mesh.corners(t);
        let n = (b - a).cross(c - a).normalize();
        let inside = |u: DVec3, v: DVec3| (v - u).cross(p - u).dot(n) >= -1e-9;
        (n.dot(p - a).abs() <= 1e-9 * (1.0 + p.length())
            && inside(a, b)
            && inside(b, c)
            && inside(c, a))
        .then_some(n)
    })
}

/// Measures the Lambert check `l`: rendered with `measuring`, expected from `described`.
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    l: &LambertSpec,
) -> Result<Found, String> {
    let f = described.fixture;
    let obj = f.object(&l.object)?;
    let model = described.model;
    let path = BodyPath::of(f, &l.object, model)?;
    let camera = described.camera_x();
    let seen = path
        .seen(l.point, described.camera_t, camera, model)
        .ok_or_else(|| {
            format!(
                "the point {} of {:?} is never seen from the camera",
                l.point, l.object
            )
        })?;
    let u = path.velocity(l.point, seen.t).unwrap_or(DVec3::ZERO);
    let to_lamp = (f.scene.light.position - seen.x).normalize();
    let to_camera = -seen.direction;
    let into_frame = |d: DVec3| match (
        model.light_speed,
        model.lorentz && obj.kind == ObjectKind::VObj,
    ) {
        (LightSpeed::Infinite, _) => d,
        (LightSpeed::Finite, true) => aberrate_lorentz(d, u),
        (LightSpeed::Finite, false) => aberrate_galilean(d, u),
    };
    // The viewer is no source: the light towards it leaves the surface, so
    // its direction there is that light's propagation in the surface's
    // frame, the reverse of where light arriving from -to_camera comes from.
    let towards_viewer = -into_frame(-to_camera);
    let n = rest_normal(&obj.shape, l.point).ok_or("the point is on no triangle")?;
    let n = if n.dot(towards_viewer) < 0.0 { -n } else { n };
    let expected = n.dot(into_frame(to_lamp)).max(0.0);

    let mut plain = measuring.fixture.clone();
    (plain.spec.image.doppler, plain.spec.image.searchlight) = (false, false);
    let probe = Observer {
        fixture: &plain,
        ..*measuring
    };
    let (img, _) = probe.probe(&Probe {
        keep: &[l.object.as_str()],
        look_at: seen.x,
        hfov_deg: PROBE_FOV,
        size: (PROBE, PROBE),
        spp: 1,
    })?;
    let c = measure::color(&img, PROBE / 2, PROBE / 2);
    let m = &measuring.fixture.object(&l.object)?.material;
    let light = &measuring.fixture.scene.light;
    let lit = m.color * light.color;
    let k = (0..3)
        .max_by(|&a, &b| lit[a].total_cmp(&lit[b]))
        .unwrap_or(0);
    if c[k] >= 1.0 {
        return Err(format!(
            "the pixel read is saturated ({:?} of 255): its brightness is clipped",
            c * 255.0
        ));
    }
    let scale = lit[k] * m.diffuse;
    let reading = Reading {
        value: (c[k] - m.color[k] * light.ambient) / scale,
        tolerance: 0.5 / 255.0 / scale,
    };
    Ok(((reading, expected, Unit::Ratio), seen.direction))
}
