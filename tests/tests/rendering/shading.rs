//! Secondary rays travel on light cones too (shadows and mirrors), 4D
//! anti-aliasing blurs motion, and V_obj clocks and lifetimes are dilated.

use glam::DVec3;
use renderer::{Attitude, LightSpeed, Ray};
use renderer::{Blink, Shader};
use renderer::{
    Camera, Database, Event, FourVector, Light, Material, Mesh, Model, Motion, ObjectKind,
    RenderSettings, Scene,
};
use renderer::{Effects, Spacetime};
use vstf::oracle::{retarded, PointWorldline};
use workspace_tests::object;

/// A 4-wide horizontal plate at height 5, moving along +x at 0.9c; its
/// trailing edge is at x = 0.5 at lab time 0.
fn plate() -> renderer::SceneObject {
    let mesh = Mesh::quad(
        DVec3::ZERO,
        DVec3::new(4.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 4.0),
    );
    let start = Event::new(-100.0, DVec3::new(0.5 - 0.9 * 100.0, 5.0, -2.0));
    object(
        "plate",
        ObjectKind::HObj,
        mesh,
        Motion::Extrusion {
            start,
            extrusion: FourVector::new(200.0, DVec3::new(180.0, 0.0, 0.0)),
        },
    )
}

#[test]
fn shadows_are_cast_where_the_light_was_blocked_earlier() {
    // The floor point at the origin at lab time t sees the light (0, 10, 0)
    // along a ray that crosses the plate's height 5 at time t - 5. The plate
    // covers x = 0 for lab times in [-5/0.9 - 0.5/0.9, -0.5/0.9].
    let scene = Scene {
        objects: vec![plate()],
        light: Light {
            position: DVec3::new(0.0, 10.0, 0.0),
            color: DVec3::ONE,
            ambient: 0.2,
            spectrum: None,
        },
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    };
    let db = Database::build(&scene, false).unwrap();
    let shader = |light_speed| Shader {
        db: &db,
        light: &scene.light,
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
        pixel_angle: 0.0,
        background_band: None,
        light_speed,
        max_depth: 0,
        shadows: true,
        effects: Effects::NONE,
    };
    let (enter, leave) = (-4.5 / 0.9, -0.5 / 0.9);
    let finite = shader(LightSpeed::Finite);
    let infinite = shader(LightSpeed::Infinite);
    for t in [
        enter + 5.0 + 0.1,
        (enter + leave) / 2.0 + 5.0,
        leave + 5.0 - 0.1,
    ] {
        let p = Event::new(t, DVec3::ZERO);
        assert!(
            finite.in_shadow(p),
            "t = {t}: the plate blocked the light 5 t.units earlier"
        );
        assert!(
            !infinite.in_shadow(p),
            "t = {t}: with infinite light speed the plate has gone by"
        );
    }
    for t in [enter + 5.0 - 0.1, leave + 5.0 + 0.1] {
        assert!(
            !finite.in_shadow(Event::new(t, DVec3::ZERO)),
            "t = {t}: lit"
        );
    }
    assert!(infinite.in_shadow(Event::new((enter + leave) / 2.0, DVec3::ZERO)));
}

#[test]
fn a_mirror_shows_a_moving_object_retarded_over_the_reflected_path() {
    // A static mirror in the plane z = -5 and a small marker moving along x.
    // By the method of images, the marker seen in the mirror is the mirrored
    // worldline, retarded over the unfolded path length.
    let mirror = object(
        "mirror",
        ObjectKind::HObj,
        Mesh::quad(
            DVec3::new(-50.0, -50.0, -5.0),
            DVec3::new(100.0, 0.0, 0.0),
            DVec3::new(0.0, 100.0, 0.0),
        ),
        Motion::at_rest(DVec3::ZERO, -1e4, 1e4),
    );
    let mut mirror = mirror;
    mirror.material = Material {
        mirror: 1.0,
        ..Material::matte(DVec3::splat(0.5))
    };
    let v = DVec3::new(0.7, 0.0, 0.0);
    let start = Event::new(-200.0, DVec3::new(-140.0, 0.0, 0.0));
    let mut marker = object(
        "marker",
        ObjectKind::HObj,
        Mesh::cuboid(DVec3::splat(-0.3), DVec3::splat(0.3)),
        Motion::Extrusion {
            start,
            extrusion: FourVector::new(400.0, v * 400.0),
        },
    );
    marker.material = Material::matte(DVec3::new(1.0, 0.0, 0.0));
    let scene = Scene {
        objects: vec![mirror, marker],
        light: Light {
            position: DVec3::new(0.0, 0.0, 30.0),
            color: DVec3::ONE,
            ambient: 1.0,
            spectrum: None,
        },
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    };
    let db = Database::build(&scene, false).unwrap();
    let shader = Shader {
        db: &db,
        light: &scene.light,
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
        pixel_angle: 0.0,
        background_band: None,
        light_speed: LightSpeed::Finite,
        max_depth: 2,
        shadows: true,
        effects: Effects::NONE,
    };
    let cam = DVec3::new(0.0, 0.0, 10.0);
    let tc = 20.0;
    // Mirrored worldline: z -> -10 - z.
    let image = PointWorldline {
        t0: start.t,
        x0: DVec3::new(start.x.x, start.x.y, -10.0 - start.x.z),
        v,
    };
    let seen = retarded(&image, tc, cam).unwrap();
    let toward = |d: DVec3| {
        shader.radiance(
            &Ray::backwards(Event::new(tc, cam), d, LightSpeed::Finite),
            0,
        )
    };
    assert!(
        toward(seen.direction).x > 0.9,
        "the marker's reflection is not where the retarded image point is"
    );
    // Where the marker would be seen with no delay in the reflection, nothing red is seen.
    let instant = PointWorldline {
        t0: start.t,
        x0: image.x0,
        v,
    }
    .at(tc);
    assert!(toward((instant - cam).normalize()).x < 0.1);
}

#[test]
fn the_shutter_blurs_a_moving_edge_over_its_travel() {
    // A white plate 40 wide moving at 0.5c across the view (which spans
    // +-17.5 l.units), 20 units away, seen with a shutter of 2 t.units: its
    // one visible edge sweeps 1 l.unit.
    let v = DVec3::new(0.5, 0.0, 0.0);
    let start = Event::new(-100.0, DVec3::new(-50.0 - 40.0, -5.0, -20.0));
    let mut plate = object(
        "plate",
        ObjectKind::HObj,
        Mesh::quad(
            DVec3::ZERO,
            DVec3::new(40.0, 0.0, 0.0),
            DVec3::new(0.0, 10.0, 0.0),
        ),
        Motion::Extrusion {
            start,
            extrusion: FourVector::new(400.0, v * 400.0),
        },
    );
    plate.material = Material::matte(DVec3::ONE);
    let scene = Scene {
        objects: vec![plate],
        light: Light {
            position: DVec3::new(0.0, 0.0, 10.0),
            color: DVec3::ZERO,
            ambient: 1.0,
            spectrum: None,
        },
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    };
    let db = Database::build(&scene, false).unwrap();
    let tc = 20.0; // emission at t = 0: the leading edge is at x = 0
    let camera = Camera::new(
        Event::new(tc, DVec3::ZERO),
        Attitude::LookAt {
            look_at: DVec3::new(0.0, 0.0, -1.0),
            up: DVec3::Y,
        },
        10.0,
        200,
        20,
    )
    .unwrap();
    let row = |shutter: f64| {
        let img = renderer::render(
            &db,
            &scene,
            &camera,
            tc,
            Model::CLASSICAL,
            &RenderSettings {
                spp: 64,
                shutter,
                seed: 9,
                max_depth: 0,
                shadows: true,
                effects: Effects::NONE,
            },
        );
        (0..200)
            .map(|x| img.pixels[10 * 200 + x].x)
            .collect::<Vec<f64>>()
    };
    let ramp = |r: &[f64]| r.iter().filter(|x| **x > 0.02 && **x < 0.98).count();
    let (sharp, blurred) = (row(0.0), row(2.0));
    // Pixel footprint at 20 units: 20 * 2 tan(5 deg) * 10 / 200 l.units.
    let px = 20.0 * 2.0 * (5f64).to_radians().tan() * 10.0 / 200.0;
    let expected = 1.0 / px;
    assert!(
        ramp(&sharp) <= 2,
        "an unblurred edge spans {} pixels",
        ramp(&sharp)
    );
    let got = ramp(&blurred) as f64;
    assert!(
        abs_diff_eq!(got, expected, epsilon = 0.2 * expected + 2.0),
        "blur spans {got} pixels, expected about {expected:.1}"
    );
}

#[test]
fn a_v_obj_clock_and_lifetime_are_dilated() {
    let v = DVec3::new(0.6, 0.0, 0.0); // gamma = 1.25
    let start = Event::new(0.0, DVec3::ZERO);
    let mut obj = object(
        "clock",
        ObjectKind::VObj,
        Mesh::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)),
        Motion::Velocity {
            start,
            velocity: v,
            proper_lifetime: 8.0,
        },
    );
    obj.material.blink = Some(Blink {
        period: 2.0,
        color: DVec3::ONE,
    });
    let scene = Scene {
        objects: vec![obj],
        light: Light {
            position: DVec3::Y * 10.0,
            color: DVec3::ONE,
            ambient: 0.2,
            spectrum: None,
        },
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    };
    let rel = Database::build(&scene, true).unwrap();
    let cls = Database::build(&scene, false).unwrap();
    let (r, c) = (&rel.objects()[0], &cls.objects()[0]);
    assert!(
        abs_diff_eq!(r.lifetime().1 - r.lifetime().0, 10.0, epsilon = 1e-12),
        "lab lifetime gamma * 8"
    );
    assert_abs_diff_eq!(c.lifetime().1 - c.lifetime().0, 8.0, epsilon = 1e-12);
    // 5 lab t.units along the reference point's worldline are 4 of its own.
    let e = Event::new(5.0, v * 5.0);
    assert_abs_diff_eq!(r.proper_time(e), 4.0, epsilon = 1e-12);
    assert_abs_diff_eq!(c.proper_time(e), 5.0, epsilon = 1e-12);
    // The blink follows proper time: on in [0, 1), off in [1, 2) of each period.
    let m = &r.material;
    assert_eq!(
        m.color_at(r.proper_time(Event::new(1.2, v * 1.2))),
        DVec3::ONE
    ); // tau = 0.96
    assert_ne!(
        m.color_at(r.proper_time(Event::new(1.3, v * 1.3))),
        DVec3::ONE
    ); // tau = 1.04
       // Contraction: the box is 2/gamma long along x in the lab.
    let xs: Vec<f64> = rel
        .tetrahedra()
        .flat_map(|t| t.vertices)
        .filter(|ev| ev.t == 0.0)
        .map(|ev| ev.x.x)
        .collect();
    let len =
        xs.iter().cloned().fold(f64::MIN, f64::max) - xs.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        abs_diff_eq!(len, 1.6, epsilon = 1e-12),
        "contracted length {len}"
    );
}

/// A light at a non-finite position makes the lit colour NaN, which the
/// pixel's check then reports, instead of shading the surface as if unlit
/// (`x > 0` and `max(0)` would drop the NaN); a finite light shades it
/// finitely (the control).
#[test]
fn a_non_finite_light_direction_reaches_the_pixel_instead_of_shading_unlit() {
    let static_plate = object(
        "plate",
        ObjectKind::HObj,
        Mesh::quad(
            DVec3::new(-2.0, 0.0, -2.0),
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 4.0),
        ),
        Motion::Extrusion {
            start: Event::new(-100.0, DVec3::ZERO),
            extrusion: FourVector::new(200.0, DVec3::ZERO),
        },
    );
    let colour = |light_at: DVec3, spectral: bool| {
        let scene = Scene {
            objects: vec![static_plate.clone()],
            light: Light {
                position: light_at,
                color: DVec3::ONE,
                ambient: 0.2,
                spectrum: None,
            },
            background: DVec3::ZERO,
            sky: None,
            spacetime: Spacetime::Flat,
        };
        let db = Database::build(&scene, false).unwrap();
        let shader = Shader {
            db: &db,
            light: &scene.light,
            background: DVec3::ZERO,
            sky: None,
            spacetime: Spacetime::Flat,
            pixel_angle: 0.0,
            background_band: None,
            light_speed: LightSpeed::Finite,
            max_depth: 0,
            shadows: false,
            effects: Effects {
                doppler: spectral,
                searchlight: false,
            },
        };
        let ray = Ray::backwards(
            Event::new(0.0, DVec3::new(0.0, 5.0, 0.0)),
            DVec3::new(0.0, -1.0, 0.0),
            LightSpeed::Finite,
        );
        shader.radiance(&ray, 0)
    };
    for spectral in [false, true] {
        assert!(colour(DVec3::new(1.0, 10.0, 0.0), spectral).is_finite());
        let c = colour(DVec3::new(f64::NAN, 10.0, 0.0), spectral);
        assert!(
            !c.is_finite(),
            "spectral {spectral}: {c} shaded as if unlit"
        );
    }
}
