//! The camera's attitude, its projection and its rays.

use super::*;
use approx::assert_abs_diff_eq;

fn cam(attitude: Attitude) -> Camera {
    Camera::new(
        Event::new(0.0, DVec3::new(1.0, 2.0, 3.0)),
        attitude,
        60.0,
        64,
        48,
    )
    .unwrap()
}

#[test]
fn yaw_and_pitch_turn_the_view_as_documented() {
    let close = |a: DVec3, b: DVec3| (a - b).length() < 1e-12;
    assert!(close(
        cam(Attitude::YawPitch {
            yaw_deg: 0.0,
            pitch_deg: 0.0
        })
        .forward,
        DVec3::NEG_Z
    ));
    assert!(close(
        cam(Attitude::YawPitch {
            yaw_deg: 90.0,
            pitch_deg: 0.0
        })
        .forward,
        DVec3::NEG_X
    ));
    let up = cam(Attitude::YawPitch {
        yaw_deg: 0.0,
        pitch_deg: 30.0,
    });
    assert!(close(up.forward, DVec3::new(0.0, 0.5, -(0.75f64).sqrt())));
    assert!(up.up.y > 0.0 && close(up.right, DVec3::X));
    // The same view by look-at.
    let look = cam(Attitude::LookAt {
        look_at: DVec3::new(1.0, 2.0, 3.0) + DVec3::NEG_X,
        up: DVec3::Y,
    });
    assert!(close(
        look.forward,
        cam(Attitude::YawPitch {
            yaw_deg: 90.0,
            pitch_deg: 0.0
        })
        .forward
    ));
}

#[test]
fn pixel_of_inverts_direction() {
    let c = cam(Attitude::LookAt {
        look_at: DVec3::ZERO,
        up: DVec3::Y,
    });
    for (px, py) in [(0.5, 0.5), (32.0, 24.0), (63.2, 10.7)] {
        let (x, y) = c.pixel_of(c.direction(px, py)).unwrap();
        assert_abs_diff_eq!(x, px, epsilon = 1e-9);
        assert_abs_diff_eq!(y, py, epsilon = 1e-9);
    }
    assert!(c.pixel_of(-c.forward).is_none());
    assert!(Camera::new(
        Event::new(0.0, DVec3::ZERO),
        Attitude::LookAt {
            look_at: DVec3::Y,
            up: DVec3::Y
        },
        60.0,
        8,
        8
    )
    .is_none());
}

/// Each lane of `Camera::rays` is `Camera::ray` of its own camera to
/// the bit: at rest, moving (Galilean and Lorentz, two speeds) and
/// without light travel, lanes mixed in one call.
#[test]
fn rays_of_several_lanes_are_each_lanes_own_ray() {
    let at_rest = cam(Attitude::LookAt {
        look_at: DVec3::ZERO,
        up: DVec3::Y,
    });
    let v = DVec3::new(0.3, -0.5, 0.6);
    let lanes = [
        at_rest,
        at_rest.moving(v, Model::CLASSICAL).unwrap(),
        at_rest.moving(v, Model::RELATIVISTIC).unwrap(),
        at_rest.moving(v * 0.5, Model::RELATIVISTIC).unwrap(),
        at_rest.moving(v, Model::INFINITE).unwrap(),
    ];
    let at = [
        (0.5, 0.5, 0.0),
        (32.0, 24.0, 1.5),
        (63.2, 10.7, -2.0),
        (12.25, 47.9, 0.25),
        (5.0, 6.0, 3.0),
    ];
    for light in [LightSpeed::Finite, LightSpeed::Infinite] {
        let rays = Camera::rays(&lanes.each_ref(), &at, light);
        for ((c, &(px, py, t)), ray) in lanes.iter().zip(&at).zip(rays) {
            let own = c.ray(px, py, t, light);
            assert_eq!(format!("{own:?}"), format!("{ray:?}"));
        }
        // Control: the Lorentz camera's ray through the Galilean lane's
        // pixel is not the Galilean lane's ray.
        let swapped = Camera::rays(&[&lanes[2]], &[at[1]], light)[0];
        assert_ne!(
            format!("{swapped:?}"),
            format!("{:?}", lanes[1].ray(32.0, 24.0, 1.5, light))
        );
    }
}
