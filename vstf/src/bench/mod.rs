//! `vstf bench`: the speed figures of the README, measured side by side in
//! one run. Times are the best of several runs of the same work, on this
//! machine; what is quoted elsewhere are ratios between them. Section 7
//! ([`embree`]) runs Intel Embree on the same triangles ([`tori`]) when it
//! is installed.

pub mod embree;
pub mod paired;
mod primary;
pub mod tori;

use crate::fixture::{Fixture, Overrides, View};
use crate::project::Project;
use glam::DVec3;
use renderer::{
    Attitude, Camera, Database, Event, FourVector, Light, Material, Mesh, Model, Motion,
    ObjectKind, RenderSettings, Scene, SceneObject, Shape, Traversal,
};
use renderer::{Image, Spacetime, SplitMix64};
use std::fmt::Write as _;
use std::time::Instant;

/// The best of `runs` timings of `work`, in seconds.
fn best_of(runs: usize, mut work: impl FnMut()) -> f64 {
    (0..runs)
        .map(|_| {
            let t = Instant::now();
            work();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The fixture `name` of the benchmark's project at `w` x `h`, 1 sample per pixel.
fn fixture_view(
    plan: &Plan,
    name: &str,
    (w, h): (u32, u32),
    model: Model,
) -> Result<(Fixture, View), String> {
    let f = plan.project.load(name).map_err(|e| e.to_string())?;
    let view = crate::run::view(
        &f,
        &Overrides {
            model: Some(model),
            width: Some(w),
            height: Some(h),
            spp: Some(1),
            ..Default::default()
        },
    )?;
    Ok((f, view))
}

/// A scene of `n` boxes (12 triangles, 36 tetrahedra each) scattered over
/// a 100-unit cube, each moving at up to 0.6c for 400 t.units.
pub fn boxes(n: usize, seed: u64) -> Scene {
    tessellated_boxes(n, 1, seed)
}

/// A box whose every face is cut into k x k squares (12 k^2 triangles).
pub fn tessellated_cuboid(half: DVec3, k: u32) -> Mesh {
    let mut m = Mesh::default();
    let kf = f64::from(k);
    // Each face: a corner of the unit cube [-1, 1]^3 and two edges spanning it.
    let faces = [
        (
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ),
        (
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ),
        (
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(0.0, 0.0, 2.0),
            DVec3::new(0.0, 2.0, 0.0),
        ),
        (
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(0.0, 0.0, 2.0),
        ),
        (
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 2.0),
        ),
        (
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(0.0, 0.0, 2.0),
            DVec3::new(2.0, 0.0, 0.0),
        ),
    ];
    for (corner, u, v) in faces {
        for i in 0..k {
            for j in 0..k {
                let c = corner + u * (f64::from(i) / kf) + v * (f64::from(j) / kf);
                m.append(
                    &Mesh::quad(c * half, u / kf * half, v / kf * half),
                    DVec3::ZERO,
                );
            }
        }
    }
    m
}

/// [`boxes`] with every face cut into k x k squares: the same picture with
/// 36 k^2 tetrahedra per box.
pub fn tessellated_boxes(n: usize, k: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let objects = (0..n)
        .map(|i| {
            let half = DVec3::splat(rng.range(0.3, 0.8));
            let at = DVec3::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
            );
            let dir = DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            )
            .normalize_or_zero();
            let v = dir * rng.range(0.0, 0.6);
            let color = DVec3::new(
                rng.range(0.2, 1.0),
                rng.range(0.2, 1.0),
                rng.range(0.2, 1.0),
            );
            SceneObject {
                name: format!("box {i}"),
                kind: ObjectKind::HObj,
                shape: Shape::Mesh(if k == 1 {
                    Mesh::cuboid(-half, half)
                } else {
                    tessellated_cuboid(half, k)
                }),
                motion: Motion::Extrusion {
                    start: Event::new(-300.0, at - v * 300.0),
                    extrusion: FourVector::new(400.0, v * 400.0),
                },
                material: Material::matte(color),
                face_materials: Vec::new(),
            }
        })
        .collect();
    Scene {
        objects,
        light: Light {
            position: DVec3::new(60.0, 200.0, 150.0),
            color: DVec3::ONE,
            ambient: 0.3,
            spectrum: None,
        },
        background: DVec3::ZERO,
        sky: None,
        spacetime: Spacetime::Flat,
    }
}

fn boxes_camera(w: u32, h: u32) -> Camera {
    Camera::new(
        Event::new(0.0, DVec3::new(0.0, 0.0, 160.0)),
        Attitude::LookAt {
            look_at: DVec3::ZERO,
            up: DVec3::Y,
        },
        45.0,
        w,
        h,
    )
    .expect("a valid camera")
}

fn render_boxes(db: &Database, scene: &Scene, cam: &Camera) -> renderer::Image {
    renderer::render(
        db,
        scene,
        cam,
        0.0,
        Model::CLASSICAL,
        &RenderSettings::default(),
    )
}

/// This process's resident memory and its peak, bytes (Linux; zero
/// elsewhere).
fn memory() -> (u64, u64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<u64>().ok())
            .map_or(0, |kb| kb * 1024)
    };
    (field("VmRSS:"), field("VmHWM:"))
}

/// Sizes of one benchmark run.
struct Plan {
    quick: bool,
    /// Image size for sections 1, 2 and 4.
    w: u32,
    h: u32,
    /// Timed repetitions; the best is kept.
    runs: usize,
    /// The project whose `flange` and `teaser` fixtures are timed.
    project: Project,
}

/// Runs the benchmark and returns the report. `quick` uses smaller images
/// and scenes (for a smoke test); the README quotes a full run.
pub fn run(project: &Project, quick: bool) -> Result<String, String> {
    let (w, h) = if quick { (160, 90) } else { (640, 360) };
    let plan = Plan {
        quick,
        w,
        h,
        runs: if quick { 1 } else { 3 },
        project: project.clone(),
    };
    let mut out = String::new();
    let threads = rayon::current_num_threads();
    let level = renderer::SimdLevel::best();
    let _ = writeln!(
        out,
        "vstf bench ({} run, {threads} threads; best of {}; node tests at {level})",
        if quick { "quick" } else { "full" },
        plan.runs
    );
    // 5 first, while the process is small.
    memory_per_tetrahedron(&plan, &mut out)?;
    rays_per_second(&plan, &mut out)?;
    against_brute_force(&plan, &mut out)?;
    growth(&plan, &mut out)?;
    teaser_frame(&plan, &mut out)?;
    let dir = plan
        .project
        .root()
        .join("target")
        .join("vstf")
        .join("bench");
    embree::section(&dir, quick, &mut out)?;
    curved_spacetime(&plan, &mut out)?;
    Ok(out)
}

/// 5. Peak memory per million tetrahedra.
fn memory_per_tetrahedron(plan: &Plan, out: &mut String) -> Result<(), String> {
    let n_mem = if plan.quick { 2_800 } else { 27_778 };
    let (rss0, _) = memory();
    let scene = boxes(n_mem, 5);
    let db = Database::build(&scene, false).map_err(|e| e.to_string())?;
    let tets = db.tetrahedron_count();
    let (_, peak) = memory();
    drop(db);
    let per_million = (peak.saturating_sub(rss0)) as f64 / 1e6 / (tets as f64 / 1e6);
    let _ = writeln!(out, "\n5. memory: building {tets} tetrahedra raised the peak by {:.0} MB: {per_million:.0} MB per million tetrahedra", (peak.saturating_sub(rss0)) as f64 / 1e6);
    Ok(())
}

/// 1. Rays per second; 2. relativistic against infinite.
fn rays_per_second(plan: &Plan, out: &mut String) -> Result<(), String> {
    let (w, h, runs) = (plan.w, plan.h, plan.runs);
    let _ = writeln!(
        out,
        "\n1. primary rays per second at {w}x{h}, 1 sample per pixel"
    );
    let _ = writeln!(
        out,
        "   {:10} {:>16} {:>28}",
        "scene", "primary only", "with shadows + reflections"
    );
    let mut ratios = Vec::new();
    for name in ["flange", "teaser"] {
        let (f, view) = fixture_view(plan, name, (w, h), Model::RELATIVISTIC)?;
        let db = crate::run::database(&f, true, Traversal::Bvh)?;
        let mut primary = view;
        primary.settings.shadows = false;
        primary.settings.max_depth = 0;
        let t_primary = best_of(runs, || drop(crate::run::render_with(&db, &f, &primary)));
        let t_full = best_of(runs, || drop(crate::run::render_with(&db, &f, &view)));
        let rays = f64::from(w * h);
        let _ = writeln!(
            out,
            "   {name:10} {:>16.0} {:>28.0}",
            rays / t_primary,
            rays / t_full
        );
        let (fi, vi) = fixture_view(plan, name, (w, h), Model::INFINITE)?;
        let dbi = crate::run::database(&fi, false, Traversal::Bvh)?;
        let t_inf = best_of(runs, || drop(crate::run::render_with(&dbi, &fi, &vi)));
        ratios.push((name, t_full / t_inf));
    }
    let _ = writeln!(out, "\n2. relativistic render time / infinite (3D slice) render time, same scene and size (goal <= 1.3)");
    for (name, r) in ratios {
        let _ = writeln!(out, "   {name:10} {r:.2}x");
    }
    Ok(())
}

/// 3. Accelerated against brute force, on many moving boxes.
fn against_brute_force(plan: &Plan, out: &mut String) -> Result<(), String> {
    let counts: &[usize] = if plan.quick {
        &[28, 278]
    } else {
        &[28, 278, 2_778]
    };
    let (bw, bh) = if plan.quick { (24, 18) } else { (48, 36) };
    let _ = writeln!(
        out,
        "\n3. accelerated against brute force, N moving boxes, {bw}x{bh} (goal >= 100x at 10k)"
    );
    let _ = writeln!(
        out,
        "   {:>7} {:>9} {:>12} {:>12} {:>9}",
        "boxes", "tets", "brute (s)", "bvh (s)", "speedup"
    );
    for &n in counts {
        let scene = boxes(n, 11);
        let mut db = Database::build(&scene, false).map_err(|e| e.to_string())?;
        let small = boxes_camera(bw, bh);
        db.set_traversal(Traversal::BruteForce);
        let brute = best_of(1, || drop(render_boxes(&db, &scene, &small)));
        db.set_traversal(Traversal::Bvh);
        let reps = 20;
        let bvh = best_of(plan.runs, || {
            (0..reps).for_each(|_| drop(render_boxes(&db, &scene, &small)))
        }) / reps as f64;
        let _ = writeln!(
            out,
            "   {n:>7} {:>9} {brute:>12.4} {bvh:>12.6} {:>8.0}x",
            db.tetrahedron_count(),
            brute / bvh
        );
    }
    Ok(())
}

/// 4. Growth with the tetrahedron count at a constant picture, and build time.
fn growth(plan: &Plan, out: &mut String) -> Result<(), String> {
    let (w, h) = (plan.w, plan.h);
    let ks: &[u32] = if plan.quick { &[1, 3] } else { &[1, 3, 10, 32] };
    let _ = writeln!(out, "\n4. the same 28 moving boxes, faces cut k x k, at {w}x{h} (goal: frame time about logarithmic)");
    let _ = writeln!(
        out,
        "   {:>4} {:>9} {:>12} {:>12} {:>14}",
        "k", "tets", "build (s)", "frame (s)", "build / frame"
    );
    let mut previous: Option<(f64, usize)> = None;
    for &k in ks {
        let scene = tessellated_boxes(28, k, 11);
        let t = Instant::now();
        let db = Database::build(&scene, false).map_err(|e| e.to_string())?;
        let build = t.elapsed().as_secs_f64();
        let frame = best_of(plan.runs, || {
            drop(render_boxes(&db, &scene, &boxes_camera(w, h)))
        });
        let n = db.tetrahedron_count();
        let growth = previous.map_or(String::new(), |(f, m)| {
            format!(
                "  (frame x{:.2} for tets x{:.1})",
                frame / f,
                n as f64 / m as f64
            )
        });
        previous = Some((frame, n));
        let _ = writeln!(
            out,
            "   {k:>4} {n:>9} {build:>12.4} {frame:>12.4} {:>14.2}{growth}",
            build / frame
        );
    }
    Ok(())
}

/// 6. The main job's frame goal.
fn teaser_frame(plan: &Plan, out: &mut String) -> Result<(), String> {
    let (fw, fh) = if plan.quick { (480, 270) } else { (1920, 1080) };
    let (f, view) = fixture_view(plan, "teaser", (fw, fh), Model::RELATIVISTIC)?;
    let t = Instant::now();
    let db = crate::run::database(&f, true, Traversal::Bvh)?;
    let build = t.elapsed().as_secs_f64();
    // Frame after frame into the same image, as an animation renders.
    let mut spent = Image::default();
    let frame = best_of(plan.runs, || {
        let image = crate::run::render_reusing(&db, &f, &view, std::mem::take(&mut spent));
        spent = image.unwrap_or_default();
    });
    let _ = writeln!(
        out,
        "\n6. one {fw}x{fh} teaser frame, relativistic, shadows and reflections, 1 sample per pixel: {frame:.2} s (+ {build:.3} s to build the database once; goal <= 0.3 s)"
    );
    Ok(())
}

/// Section 8, light bent by a mass: the `lensed-flange` fixture against the same
/// scene in flat spacetime, each frame with its database built once.
fn curved_spacetime(plan: &Plan, out: &mut String) -> Result<(), String> {
    let (fw, fh) = if plan.quick { (320, 180) } else { (1920, 1080) };
    let (bent, view) = fixture_view(plan, "lensed-flange", (fw, fh), Model::RELATIVISTIC)?;
    let mut flat = bent.clone();
    flat.scene.spacetime = Spacetime::Flat;
    let time = |f: &Fixture| -> Result<f64, String> {
        let db = crate::run::database(f, view.model.lorentz, Traversal::Bvh)?;
        crate::run::render_with(&db, f, &view)?;
        Ok(best_of(plan.runs, || {
            drop(crate::run::render_with(&db, f, &view))
        }))
    };
    let (curved, straight) = (time(&bent)?, time(&flat)?);
    let _ = writeln!(
        out,
        "\n8. one {fw}x{fh} lensed-flange frame (a mass M = 0.02 in front of the flange at 0.866c), 1 sample per pixel: {curved:.2} s curved against {straight:.2} s with the mass taken away: {:.1}x (goal <= 5x)",
        curved / straight
    );
    Ok(())
}
