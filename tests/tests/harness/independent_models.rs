//! The measurements and the oracle model the camera, the colorimetry and
//! the Lorentz boost on their own (so that a renderer bug cannot cancel
//! out). Here each own model is compared with the renderer's on random
//! inputs, and a deliberately wrong model (negative control) must be caught
//! by the same comparison.

use glam::DVec3;
use renderer::{self as spectrum, Spectrum};
use renderer::{Attitude, Boost, Camera, Event, FourVector, Model};
use vstf::measure::colorimetry::{observer, xyz_of_rgb, Blackbody, Chromaticity};
use vstf::measure::{Kinematics, Pinhole};
use vstf::oracle::to_frame_of;

/// A small deterministic generator (xorshift64*), uniform in [lo, hi).
struct Random(u64);

impl Random {
    fn next(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let u = (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }

    fn vec(&mut self, r: f64) -> DVec3 {
        DVec3::new(self.next(-r, r), self.next(-r, r), self.next(-r, r))
    }
}

/// A random camera as the renderer builds it and as the measurements do.
struct Pair {
    camera: Camera,
    pinhole: Pinhole,
}

fn random_pair(rng: &mut Random, model: Model, pinhole_vfov_error: f64) -> Pair {
    let position = rng.vec(10.0);
    let look_at = position + rng.vec(5.0);
    let vfov = rng.next(5.0, 120.0);
    let (width, height) = (rng.next(8.0, 500.0) as u32, rng.next(8.0, 500.0) as u32);
    let velocity = rng.vec(0.5);
    let kinematics = Kinematics::of(
        model.light_speed == renderer::LightSpeed::Finite,
        model.lorentz,
    );
    let camera = Camera::new(
        Event::new(rng.next(-5.0, 5.0), position),
        Attitude::LookAt {
            look_at,
            up: DVec3::Y,
        },
        vfov,
        width,
        height,
    )
    .and_then(|c| c.moving(velocity, model))
    .expect("a valid camera");
    let pinhole = Pinhole::looking_at(
        position,
        look_at,
        DVec3::Y,
        vfov + pinhole_vfov_error,
        (width, height),
    )
    .and_then(|p| p.moving(velocity, kinematics))
    .expect("a valid pinhole");
    Pair { camera, pinhole }
}

/// The largest disagreement, over random pixels, between the two models'
/// lab lines of sight, and between their pixels of random lab directions.
fn disagreement(pair: &Pair, rng: &mut Random) -> f64 {
    let (c, p) = (&pair.camera, &pair.pinhole);
    let mut worst: f64 = 0.0;
    for _ in 0..50 {
        let (px, py) = (
            rng.next(0.0, f64::from(c.width)),
            rng.next(0.0, f64::from(c.height)),
        );
        worst = worst.max((c.direction(px, py) - p.direction(px, py)).length());
        let d = c.direction(px, py);
        if let (Some(a), Some(b)) = (c.pixel_of(d), p.pixel_of(d)) {
            worst = worst.max((a.0 - b.0).hypot(a.1 - b.1) / f64::from(c.height));
        }
    }
    worst
}

#[test]
fn the_pinhole_sees_as_the_renderers_camera_does() {
    let mut rng = Random(0x9e37_79b9_7f4a_7c15);
    for model in [Model::INFINITE, Model::CLASSICAL, Model::RELATIVISTIC] {
        for _ in 0..40 {
            let pair = random_pair(&mut rng, model, 0.0);
            let d = disagreement(&pair, &mut rng);
            assert!(d < 1e-12, "{model:?}: {d}");
            let (c, p) = (&pair.camera, &pair.pinhole);
            assert_abs_diff_eq!((c.forward - p.forward).length(), 0.0, epsilon = 1e-15);
            assert_abs_diff_eq!((c.up - p.up).length(), 0.0, epsilon = 1e-15);
            assert_abs_diff_eq!((c.right - p.right).length(), 0.0, epsilon = 1e-15);
        }
    }
}

#[test]
fn a_pinhole_with_the_wrong_field_of_view_is_caught() {
    let mut rng = Random(0x1234_5678_9abc_def1);
    for model in [Model::INFINITE, Model::RELATIVISTIC] {
        for _ in 0..10 {
            let pair = random_pair(&mut rng, model, 0.01);
            let d = disagreement(&pair, &mut rng);
            assert!(d > 1e-7, "a 0.01 degree error went unseen: {d}");
        }
    }
}

#[test]
fn yaw_and_pitch_match_the_renderer() {
    let mut rng = Random(42);
    for _ in 0..20 {
        let (yaw, pitch) = (rng.next(-180.0, 180.0), rng.next(-80.0, 80.0));
        let c = Camera::new(
            Event::new(0.0, DVec3::ZERO),
            Attitude::YawPitch {
                yaw_deg: yaw,
                pitch_deg: pitch,
            },
            50.0,
            64,
            48,
        )
        .unwrap();
        let p = Pinhole::yaw_pitch(DVec3::ZERO, (yaw, pitch), 50.0, (64, 48)).unwrap();
        assert_abs_diff_eq!((c.forward - p.forward).length(), 0.0, epsilon = 1e-15);
        assert_abs_diff_eq!((c.up - p.up).length(), 0.0, epsilon = 1e-15);
    }
}

/// The renderer's linear RGB -> XYZ, as its `xyz_to_rgb` defines it.
fn renderer_xyz_of_rgb(rgb: DVec3) -> DVec3 {
    glam::DMat3::from_cols(
        spectrum::xyz_to_rgb(DVec3::X),
        spectrum::xyz_to_rgb(DVec3::Y),
        spectrum::xyz_to_rgb(DVec3::Z),
    )
    .inverse()
        * rgb
}

fn renderer_blackbody_xyz(kelvin: f64, scale: f64, d: f64) -> DVec3 {
    spectrum::xyz(&Spectrum::Blackbody { kelvin, scale }.sample_scaled(d))
}

/// Relative agreement of two vectors.
fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element() <= 1e-12 * b.abs().max_element().max(1e-300)
}

/// (Today they agree to the last bit, which keeps the doppler rows of the
/// check table unchanged; the test asks for the physics, 1e-12.)
#[test]
fn the_colorimetry_is_the_renderers() {
    let mut rng = Random(7);
    for _ in 0..200 {
        let nm = rng.next(300.0, 900.0);
        assert!(close(observer(nm), spectrum::cmf(nm)), "{nm} nm");
        let rgb = DVec3::new(rng.next(0.0, 1.0), rng.next(0.0, 1.0), rng.next(0.0, 1.0));
        assert!(close(xyz_of_rgb(rgb), renderer_xyz_of_rgb(rgb)), "{rgb}");
        let (kelvin, scale, d) = (
            rng.next(1000.0, 20000.0),
            rng.next(0.1, 3.0),
            rng.next(0.3, 3.0),
        );
        let ours = Blackbody { kelvin, scale }.xyz_shifted(d);
        assert!(close(ours, renderer_blackbody_xyz(kelvin, scale, d)));
        let c = Chromaticity::of(ours).unwrap();
        let (x, y) = spectrum::chromaticity(ours).unwrap();
        assert_abs_diff_eq!(c.x, x, epsilon = 1e-15);
        assert_abs_diff_eq!(c.y, y, epsilon = 1e-15);
    }
}

#[test]
fn a_blackbody_at_the_wrong_temperature_is_caught() {
    let ours = Blackbody {
        kelvin: 4000.0 * 1.001,
        scale: 1.0,
    }
    .xyz_shifted(1.0);
    let theirs = renderer_blackbody_xyz(4000.0, 1.0, 1.0);
    let (a, b) = (
        Chromaticity::of(ours).unwrap(),
        Chromaticity::of(theirs).unwrap(),
    );
    assert!(a.distance_squared(b).sqrt() > 1e-5);
}

#[test]
fn the_oracles_boost_is_the_renderers() {
    let mut rng = Random(99);
    for _ in 0..100 {
        let u = rng.vec(0.55);
        let (dt, dx) = (rng.next(-10.0, 10.0), rng.vec(10.0));
        let (t, x) = to_frame_of(dt, dx, u).unwrap();
        let theirs = Boost::new(u).unwrap().to_rest(FourVector::new(dt, dx));
        assert_abs_diff_eq!(t, theirs.t, epsilon = 1e-12);
        assert_abs_diff_eq!((x - theirs.x).length(), 0.0, epsilon = 1e-12);
        // Negative control: the boost by +u is another frame.
        let wrong = Boost::new(u).unwrap().to_lab(FourVector::new(dt, dx));
        assert!((wrong.x - x).length() > 1e-9 || u.dot(dx).abs() + dt.abs() < 1e-6);
    }
    assert!(to_frame_of(0.0, DVec3::X, DVec3::new(0.8, 0.6, 0.0)).is_none());
}
