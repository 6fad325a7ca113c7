//! The sky: an equirectangular image at infinity, seen where a ray meets
//! nothing, by the lab direction its light came from (u = 1/2 +
//! atan2(x, z) / 2 pi, v = acos(y) / pi; the image's centre faces +z).

use glam::DVec3;
use renderer::{
    render, Attitude, Camera, Event, Light, Model, RenderSettings, Scene, Spacetime, Texels,
};
use std::sync::Arc;

const W: u32 = 8;
const H: u32 = 4;

/// A sky whose texel (i, j) is (i / 8, j / 4, 1/2): bilinear between texel
/// centres, it is (x / 8, y / 4, 1/2) at texel coordinates x = u W - 1/2,
/// y = v H - 1/2 wherever the four texels mixed do not wrap.
fn ramp() -> Arc<Texels> {
    let texels = (0..H)
        .flat_map(|j| (0..W).map(move |i| DVec3::new(f64::from(i) / 8.0, f64::from(j) / 4.0, 0.5)))
        .collect();
    Arc::new(Texels::new(W, H, texels).unwrap())
}

fn scene(sky: Option<Arc<Texels>>, spacetime: Spacetime) -> Scene {
    Scene {
        objects: Vec::new(),
        light: Light::white(DVec3::new(0.0, 10.0, 0.0), 0.3),
        background: DVec3::new(0.9, 0.1, 0.1),
        sky,
        spacetime,
    }
}

/// The one pixel of a 1 x 1 image from a camera at `at` looking along `d`.
fn seen(scene: &Scene, at: DVec3, d: DVec3) -> DVec3 {
    let db = renderer::Database::build(scene, true).unwrap();
    let up = if d.cross(DVec3::Y).length() > 1e-9 {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let look = Attitude::LookAt {
        look_at: at + d,
        up,
    };
    let camera = Camera::new(Event::new(0.0, at), look, 10.0, 1, 1).unwrap();
    let settings = RenderSettings::default();
    render(&db, scene, &camera, 0.0, Model::RELATIVISTIC, &settings).pixels[0]
}

#[test]
fn a_flat_scene_shows_the_sky_texel_of_each_direction() {
    let s = scene(Some(ramp()), Spacetime::Flat);
    let r = std::f64::consts::FRAC_1_SQRT_2;
    // +z: u = 1/2, v = 1/2, texel coordinates (3.5, 1.5).
    let cases = [
        (DVec3::Z, DVec3::new(3.5 / 8.0, 1.5 / 4.0, 0.5)),
        // 45 degrees towards +x: u = 5/8, x = 4.5.
        (DVec3::new(r, 0.0, r), DVec3::new(4.5 / 8.0, 1.5 / 4.0, 0.5)),
        // 45 degrees towards -x: u = 3/8, x = 2.5.
        (
            DVec3::new(-r, 0.0, r),
            DVec3::new(2.5 / 8.0, 1.5 / 4.0, 0.5),
        ),
        // 45 degrees up: v = 1/4, y = 0.5.
        (DVec3::new(0.0, r, r), DVec3::new(3.5 / 8.0, 0.5 / 4.0, 0.5)),
    ];
    for (d, expected) in cases {
        let c = seen(&s, DVec3::new(1.0, 2.0, 3.0), d);
        assert_abs_diff_eq!(c.x, expected.x, epsilon = 1e-12);
        assert_abs_diff_eq!(c.y, expected.y, epsilon = 1e-12);
        assert_abs_diff_eq!(c.z, expected.z, epsilon = 1e-12);
    }
    // The control: without the sky, the background colour in every direction.
    let plain = scene(None, Spacetime::Flat);
    assert_eq!(seen(&plain, DVec3::ZERO, DVec3::Z), plain.background);
    assert_ne!(seen(&s, DVec3::ZERO, DVec3::Z), plain.background);
}

/// Looking straight away from a mass, light comes radially and is not
/// bent: the sky shows the texel of the view direction, as in flat
/// spacetime. Looking past it, the sky is displaced (the control).
#[test]
fn a_radial_ray_shows_the_unbent_sky_and_a_grazing_one_a_bent_sky() {
    let hole = Spacetime::of_mass(1.0, DVec3::ZERO);
    let (bent, flat) = (
        scene(Some(ramp()), hole),
        scene(Some(ramp()), Spacetime::Flat),
    );
    let at = DVec3::new(0.0, 0.0, -20.0);
    let away = seen(&bent, at, DVec3::NEG_Z);
    assert_abs_diff_eq!(away.x, seen(&flat, at, DVec3::NEG_Z).x, epsilon = 1e-12);
    let past = (DVec3::new(8.0, 0.0, 0.0) - at).normalize();
    let (b, f) = (seen(&bent, at, past), seen(&flat, at, past));
    // Light passing 8 M from the mass turns through about 4M/b = 0.5 rad:
    // u moves by about 0.08, x by more than half a texel.
    assert!((b.x - f.x).abs() > 0.5 / 8.0, "{b} vs {f}");
}
