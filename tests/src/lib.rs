//! Helpers shared by the workspace-level integration tests in `tests/tests/`.

use glam::DVec3;
use renderer::{
    Event, FourVector, Light, Material, Mesh, Motion, ObjectKind, Scene, SceneObject, Shape,
};
use renderer::{Image, Spacetime, SplitMix64};

/// An image's pixels as their bits, for comparisons to the bit.
pub fn bits(img: &Image) -> Vec<[u64; 3]> {
    img.pixels
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect()
}

/// A random point in the cube [-r, r]^3.
pub fn point(rng: &mut SplitMix64, r: f64) -> DVec3 {
    DVec3::new(rng.range(-r, r), rng.range(-r, r), rng.range(-r, r))
}

/// A random unit vector.
pub fn unit(rng: &mut SplitMix64) -> DVec3 {
    loop {
        let p = point(rng, 1.0);
        let l = p.length();
        if l > 0.1 && l <= 1.0 {
            return p / l;
        }
    }
}

/// A random non-degenerate triangle mesh of `n` triangles within [-r, r]^3.
pub fn random_mesh(rng: &mut SplitMix64, n: usize, r: f64) -> Mesh {
    let mut m = Mesh::default();
    while m.triangles.len() < n {
        let (a, b, c) = (point(rng, r), point(rng, r), point(rng, r));
        if (b - a).cross(c - a).length() > 0.05 * r * r {
            let k = m.vertices.len() as u32;
            m.vertices.extend([a, b, c]);
            m.triangles.push([k, k + 1, k + 2]);
        }
    }
    m
}

/// A random motion: subluminal (up to 0.95c) unless `superluminal`.
pub fn random_motion(rng: &mut SplitMix64, superluminal: bool) -> Motion {
    let speed = if superluminal {
        rng.range(1.05, 3.0)
    } else {
        rng.range(0.0, 0.95)
    };
    let v = unit(rng) * speed;
    let dt = rng.range(5.0, 60.0);
    Motion::Extrusion {
        start: Event::new(rng.range(-40.0, -10.0), point(rng, 3.0)),
        extrusion: FourVector::new(dt, v * dt),
    }
}

/// A scene of the given objects under a light far above.
pub fn scene(objects: Vec<SceneObject>) -> Scene {
    Scene {
        objects,
        light: Light {
            position: DVec3::new(0.0, 100.0, 0.0),
            color: DVec3::ONE,
            ambient: 0.3,
            spectrum: None,
        },
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    }
}

/// An object named `name` of the given kind, mesh and motion, matte orange
/// (0.8, 0.5, 0.2), neither an analytic sphere nor blinking.
pub fn object(name: &str, kind: ObjectKind, mesh: Mesh, motion: Motion) -> SceneObject {
    SceneObject {
        name: name.into(),
        kind,
        shape: Shape::Mesh(mesh),
        motion,
        material: Material::matte(DVec3::new(0.8, 0.5, 0.2)),
        face_materials: Vec::new(),
    }
}

/// This repository as a vstf project: its `fixtures/` and `golden/`.
pub fn repo() -> vstf::Project {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    vstf::Project::at(&root).expect("the repository is a project")
}

/// One of this repository's fixtures, by name.
pub fn fixture(name: &str) -> vstf::Fixture {
    repo().load(name).unwrap_or_else(|e| panic!("{e}"))
}

/// One of this repository's fixtures with `edit` applied to its JSON, parsed
/// (named by its file, so errors name it).
pub fn fixture_with(name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> vstf::Fixture {
    let (file, v) = edited(name, edit);
    vstf::Fixture::parse(&v.to_string(), &file).unwrap_or_else(|e| panic!("{e}"))
}

/// The error of one of this repository's fixtures with `edit` applied to its
/// JSON, which must be refused.
pub fn fixture_error_with(name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let (file, v) = edited(name, edit);
    match vstf::Fixture::parse(&v.to_string(), &file) {
        Ok(_) => panic!("a bad fixture was accepted: {v}"),
        Err(e) => e.to_string(),
    }
}

/// The file of one of this repository's fixtures and its JSON with `edit`
/// applied.
fn edited(
    name: &str,
    edit: impl FnOnce(&mut serde_json::Value),
) -> (std::path::PathBuf, serde_json::Value) {
    let file = repo().fixtures_dir().join(format!("{name}.json"));
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    edit(&mut v);
    (file, v)
}

/// The rows of the checks `described` declares, measured on renders of
/// `rendered` (the same scene, or an altered copy) at quick effort.
pub fn declared_rows(rendered: &vstf::Fixture, described: &vstf::Fixture) -> Vec<vstf::Row> {
    vstf::check::evaluate(rendered, described, &vstf::Effort::QUICK)
        .unwrap_or_else(|e| panic!("{e}"))
        .quantities
        .into_iter()
        .map(|q| q.judge(&described.name))
        .collect()
}
