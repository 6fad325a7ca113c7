//! Textures are painted in the object's own frame: a moving plate's
//! checkerboard is the rest-frame pattern, and a texture's colours are
//! shaded exactly as a material's colour would be, Doppler shift included.

use glam::DVec3;
use renderer::Spacetime;
use renderer::{
    render, Attitude, Axes, Camera, Database, Effects, Event, Light, LightSpeed, Material, Mesh,
    Model, Motion, ObjectKind, Ray, RenderSettings, Scene, SceneObject, Shader, Shape, Texture,
};

const V: f64 = 0.9;

/// A 4 x 4 plate in the plane z = 0 of its frame, moving along +x at 0.9c,
/// its reference point passing x = 0 at lab time 0 (a V_obj: contracted).
fn plate(material: Material) -> SceneObject {
    SceneObject {
        name: "plate".into(),
        kind: ObjectKind::VObj,
        shape: Shape::Mesh(Mesh::quad(
            DVec3::new(-2.0, -2.0, 0.0),
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(0.0, 4.0, 0.0),
        )),
        motion: Motion::Velocity {
            start: Event::new(-100.0, DVec3::new(-100.0 * V, 0.0, 0.0)),
            velocity: DVec3::new(V, 0.0, 0.0),
            proper_lifetime: 200.0,
        },
        material,
        face_materials: Vec::new(),
    }
}

fn ball(material: Material) -> SceneObject {
    SceneObject {
        name: "ball".into(),
        kind: ObjectKind::VObj,
        shape: Shape::Sphere { radius: 1.5 },
        motion: Motion::Velocity {
            start: Event::new(-100.0, DVec3::new(3.0 - 50.0, 1.0, -1.0)),
            velocity: DVec3::new(0.5, 0.0, 0.0),
            proper_lifetime: 200.0,
        },
        material,
        face_materials: Vec::new(),
    }
}

fn scene(objects: Vec<SceneObject>, ambient: f64) -> Scene {
    Scene {
        objects,
        light: Light::white(DVec3::new(4.0, 10.0, 12.0), ambient),
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    }
}

fn checker(colors: [DVec3; 2]) -> Material {
    Material {
        texture: Some(Texture::Checkerboard {
            size: 0.5,
            colors,
            axes: Axes([true, true, false]),
        }),
        ..Material::matte(DVec3::new(0.3, 0.6, 0.9))
    }
}

fn image(scene: &Scene, effects: Effects) -> Vec<DVec3> {
    let db = Database::build(scene, true).unwrap();
    let at = Event::new(12.0, DVec3::new(0.0, 0.0, 12.0));
    let look = Attitude::LookAt {
        look_at: DVec3::ZERO,
        up: DVec3::Y,
    };
    let camera = Camera::new(at, look, 50.0, 48, 36).unwrap();
    let settings = RenderSettings {
        effects,
        ..RenderSettings::default()
    };
    render(&db, scene, &camera, 12.0, Model::RELATIVISTIC, &settings).pixels
}

/// A checkerboard of one colour twice shades exactly as that material
/// colour (no texture), in RGB, with the Doppler shift (the colour's
/// spectral uplift) and with the searchlight; two colours differ.
#[test]
fn texture_colours_shade_as_material_colours_do() {
    let c = DVec3::new(0.7, 0.4, 0.2);
    let effects = [
        Effects::NONE,
        Effects {
            doppler: true,
            searchlight: false,
        },
        Effects {
            doppler: true,
            searchlight: true,
        },
    ];
    for fx in effects {
        let plain = scene(
            vec![plate(Material::matte(c)), ball(Material::matte(c))],
            0.3,
        );
        let one = scene(vec![plate(checker([c, c])), ball(checker([c, c]))], 0.3);
        let two = scene(
            vec![
                plate(checker([c, DVec3::ONE])),
                ball(checker([c, DVec3::ONE])),
            ],
            0.3,
        );
        let plain = image(&plain, fx);
        assert!(
            plain.iter().any(|p| *p != DVec3::ZERO),
            "{fx:?}: the objects are seen"
        );
        assert_eq!(image(&one, fx), plain, "{fx:?}");
        assert_ne!(image(&two, fx), plain, "{fx:?}: the control");
    }
}

/// Every hit on the moving plate shows the colour of the rest-frame cell
/// it lies in: x' = gamma (x - v t), y' = y. The lab's contracted
/// coordinate (x - v t) paints a different pattern (the control).
#[test]
fn a_moving_plates_checkerboard_is_its_rest_frame_pattern() {
    let (a, b) = (DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.0, 0.0, 1.0));
    let lit = Light {
        position: DVec3::new(0.0, 0.0, 100.0),
        color: DVec3::ZERO,
        ambient: 1.0,
        spectrum: None,
    };
    let s = Scene {
        light: lit,
        ..scene(vec![plate(checker([a, b]))], 1.0)
    };
    let db = Database::build(&s, true).unwrap();
    let shader = Shader {
        db: &db,
        light: &s.light,
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
        pixel_angle: 0.0,
        background_band: None,
        light_speed: LightSpeed::Finite,
        max_depth: 0,
        shadows: false,
        effects: Effects::NONE,
    };
    let gamma = 1.0 / (1.0 - V * V).sqrt();
    let parity = |x: f64, y: f64| ((x / 0.5).floor() + (y / 0.5).floor()).rem_euclid(2.0) != 0.0;
    let (mut hits, mut lab_agrees) = (0, 0);
    for i in 0..40 {
        for j in 0..40 {
            let target = DVec3::new(-3.0 + 0.15 * f64::from(i), -3.0 + 0.15 * f64::from(j), 0.0);
            let origin = Event::new(10.0, DVec3::new(0.0, 0.0, 10.0));
            let ray = Ray::backwards(origin, (target - origin.x).normalize(), LightSpeed::Finite);
            let Some(hit) = db.closest_hit(&ray, (0.0, f64::INFINITY)) else {
                continue;
            };
            let e = hit.event;
            let along = e.x.x - V * e.t;
            let (rest, lab) = (parity(gamma * along, e.x.y), parity(along, e.x.y));
            let near_wall = |x: f64| ((x / 0.5) - (x / 0.5).round()).abs() < 1e-6;
            if near_wall(gamma * along) || near_wall(e.x.y) {
                continue;
            }
            let color = shader.radiance(&ray, 0);
            assert_eq!(color, if rest { b } else { a }, "at {e:?}");
            hits += 1;
            lab_agrees += usize::from(rest == lab);
        }
    }
    assert!(hits > 200, "{hits} hits");
    assert!(
        lab_agrees < hits * 3 / 4,
        "the lab's pattern differs: {lab_agrees} of {hits}"
    );
}

/// A per-face material carries its texture: the plate whose two triangles
/// are of face material 1, a checkerboard, renders exactly as the plate
/// whose own material is that checkerboard; the face material's plain
/// colour alone (the texture lost) renders differently (the control).
#[test]
fn a_face_materials_texture_is_painted_on_its_triangles() {
    let (a, b) = (DVec3::new(0.9, 0.2, 0.1), DVec3::new(0.1, 0.3, 0.9));
    let own = scene(vec![plate(checker([a, b]))], 0.3);
    let by_face = |face: Material| {
        let mut p = plate(Material::matte(DVec3::new(0.5, 0.5, 0.5)));
        if let Shape::Mesh(mesh) = &mut p.shape {
            mesh.materials = vec![1; mesh.triangles.len()];
        }
        p.face_materials = vec![face];
        scene(vec![p], 0.3)
    };
    let expected = image(&own, Effects::NONE);
    assert_eq!(image(&by_face(checker([a, b])), Effects::NONE), expected);
    let untextured = Material {
        texture: None,
        ..checker([a, b])
    };
    assert_ne!(image(&by_face(untextured), Effects::NONE), expected);
}
