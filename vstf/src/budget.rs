//! How much work and memory a command may take before it asks for
//! `--force`: an estimate made before anything is built or rendered, so
//! that an absurd fixture or flag is refused in a moment, with the
//! estimate, instead of running for a day or aborting on a failed
//! allocation.
//!
//! The figures behind the estimates are this project's own, measured by
//! `vstf bench` on the 2-core machine it is developed on (README,
//! Performance): about 200-250 bytes at peak per triangle of a uniformly
//! moving mesh (section 7), and between 2.4 and 3.9 million rays per second
//! at 640x360. A keyframe interval's prism keeps its record, six corner
//! events and three prepared tetrahedron solves (744 bytes) besides its
//! share of the hierarchy and of the build's items. The estimates round
//! both the safe way.

use crate::error::Error;
use renderer::{Motion, Scene, Shape};
use std::fmt;

/// Peak memory per prism of a uniformly moving triangle (tested whole in
/// its comoving frame), bytes (bench: 200-250).
pub(crate) const BYTES_PER_TRANSLATED_PRISM: u64 = 300;

/// Peak memory per prism of a keyframe interval (tested as three
/// tetrahedra), bytes: 744 stored, and its share of the hierarchy and of
/// the build's items.
pub(crate) const BYTES_PER_KEYFRAMED_PRISM: u64 = 1000;

/// Primary rays per second assumed for an estimate (bench: 2.4 to 3.9
/// million with shadows and mirrors on 2 cores; a tenth of that leaves room
/// for deep mirrors and slow machines).
pub(crate) const RAYS_PER_SECOND: f64 = 1.0e6;

/// The most intervals one hyperbolic motion's keyframes can give a
/// triangle (the renderer's cap on generated keyframes).
const MAX_HYPERBOLIC_INTERVALS: u64 = 100_000;

/// The most triangles the renderer's cut of a Born-rigid surface may add
/// to one object.
const MAX_BORN_RIGID_ADDED: u64 = 1 << 20;

/// The limits a command stays within unless forced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Peak memory of the 4D database, bytes.
    pub memory: u64,
    /// Estimated render time, seconds.
    pub seconds: f64,
}

impl Budget {
    /// The default budget: 8 GB of database and an hour of rendering.
    pub const DEFAULT: Budget = Budget {
        memory: 8_000_000_000,
        seconds: 3600.0,
    };

    /// No limit (`--force`).
    pub const UNLIMITED: Budget = Budget {
        memory: u64::MAX,
        seconds: f64::INFINITY,
    };

    /// The default budget, or none when `force`.
    pub fn forced(force: bool) -> Budget {
        if force {
            Budget::UNLIMITED
        } else {
            Budget::DEFAULT
        }
    }

    /// Refuses a scene whose database would exceed the memory budget.
    pub fn check_scene(&self, scene: &Scene) -> Result<(), String> {
        let p = prisms(scene);
        let bytes = database_bytes(scene);
        if bytes <= self.memory {
            return Ok(());
        }
        Err(format!(
            "about {} prisms ({} of them keyframe intervals'), {} of memory to build \
             (at {BYTES_PER_TRANSLATED_PRISM} bytes a uniformly moving triangle's prism, \
             {BYTES_PER_KEYFRAMED_PRISM} a keyframe interval's): over the budget of {}; \
             pass --force to build it anyway",
            p.translated.saturating_add(p.keyframed),
            p.keyframed,
            Bytes(bytes),
            Bytes(self.memory)
        ))
    }

    /// Refuses rendering `frames` frames of `width` x `height` pixels at
    /// `spp` samples beyond the time budget.
    pub fn check_work(
        &self,
        (width, height): (u32, u32),
        spp: u32,
        frames: usize,
    ) -> Result<(), Error> {
        let rays = f64::from(width) * f64::from(height) * f64::from(spp) * frames as f64;
        let seconds = rays / RAYS_PER_SECOND;
        if seconds <= self.seconds {
            return Ok(());
        }
        Err(Error::Budget {
            message: format!(
                "{frames} frame(s) of {width}x{height} at {spp} samples per pixel: {rays:.3e} rays, \
                 about {} at {RAYS_PER_SECOND:.0e} rays per second: over the budget of {}; \
                 pass --force to render anyway",
                Seconds(seconds),
                Seconds(self.seconds)
            ),
        })
    }
}

/// The estimate of the memory a scene's database takes, bytes.
pub(crate) fn database_bytes(scene: &Scene) -> u64 {
    let p = prisms(scene);
    p.translated
        .saturating_mul(BYTES_PER_TRANSLATED_PRISM)
        .saturating_add(p.keyframed.saturating_mul(BYTES_PER_KEYFRAMED_PRISM))
}

/// A kept database's fixed cost besides its prisms: the fixture, the
/// database's own structures and the hierarchies' roots, bytes.
const BYTES_PER_KEPT_DATABASE: u64 = 16 * 1024;

/// [`database_bytes`] with a database's fixed cost: what a kept one is
/// counted as (by `vstf serve`'s cache and the checks' store of renders).
pub(crate) fn kept_database_bytes(scene: &Scene) -> u64 {
    database_bytes(scene).saturating_add(BYTES_PER_KEPT_DATABASE)
}

/// How many prisms a scene's database will hold, by how they are tested.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Prisms {
    /// Of uniformly moving meshes: one per triangle.
    pub translated: u64,
    /// Of keyframed and accelerated meshes: one per triangle per interval.
    pub keyframed: u64,
}

/// How many prisms the scene's database will hold: one per triangle per
/// straight stretch of its path (one stretch for uniform motion, one per
/// keyframe interval, and for hyperbolic motion one per generated
/// interval, h = sqrt(8 tolerance A_min) long, A_min = 1/a less how far a
/// V_obj reaches behind its reference point, half the tolerance for a
/// V_obj, whose mesh is cut into more triangles; docs/physics.md).
pub fn prisms(scene: &Scene) -> Prisms {
    let own: Vec<u64> = scene.objects.iter().map(stretches).collect();
    scene
        .objects
        .iter()
        .enumerate()
        .fold(Prisms::default(), |p, (i, o)| {
            let n = surface(o).saturating_mul(shared(scene, &own, i).max(1));
            match o.motion {
                Motion::Extrusion { .. } | Motion::Velocity { .. } => Prisms {
                    translated: p.translated.saturating_add(n),
                    ..p
                },
                Motion::Keyframes(_) | Motion::Hyperbolic(_) => Prisms {
                    keyframed: p.keyframed.saturating_add(n),
                    ..p
                },
            }
        })
}

/// Object `i`'s stretches: its own (`own[i]`), or for hyperbolic motion the
/// most of any object on the same worldline, since the renderer cuts them
/// all at the finest's times.
fn shared(scene: &Scene, own: &[u64], i: usize) -> u64 {
    let Motion::Hyperbolic(h) = &scene.objects[i].motion else {
        return own[i];
    };
    let same = |o: &renderer::SceneObject| match &o.motion {
        Motion::Hyperbolic(g) => {
            renderer::Hyperbolic {
                tolerance: g.tolerance,
                ..*h
            } == *g
        }
        _ => false,
    };
    scene
        .objects
        .iter()
        .zip(own)
        .filter(|(o, _)| same(o))
        .map(|(_, n)| *n)
        .max()
        .unwrap_or(own[i])
}

/// An object's triangles (none for an analytic sphere).
fn triangles(o: &renderer::SceneObject) -> u64 {
    match &o.shape {
        Shape::Mesh(m) => m.triangles.len() as u64,
        Shape::Sphere { .. } => 0,
    }
}

/// The triangles an object is extruded as: its own, or for a V_obj under
/// hyperbolic motion (Born-rigid under the Lorentz transform) the pieces
/// its curved surface is cut into.
/// A cut adding more than the renderer's cap is refused by the renderer
/// (naming the tolerance), so the estimate counts the mesh alone.
fn surface(o: &renderer::SceneObject) -> u64 {
    match (&o.motion, &o.shape, o.kind) {
        (Motion::Hyperbolic(h), Shape::Mesh(m), renderer::ObjectKind::VObj) => {
            let cut = h.born_rigid_triangles(m);
            if cut - triangles(o) > MAX_BORN_RIGID_ADDED {
                triangles(o)
            } else {
                cut
            }
        }
        _ => triangles(o),
    }
}

/// One object's stretches: one for uniform motion, one per keyframe
/// interval, and for hyperbolic motion its own cut's intervals.
fn stretches(o: &renderer::SceneObject) -> u64 {
    match &o.motion {
        Motion::Keyframes(k) => k.len().saturating_sub(1) as u64,
        Motion::Hyperbolic(h) => {
            // The smallest A = 1/a + xi over the vertices: a V_obj may
            // be Born-rigid, its rearmost vertex on the tightest hyperbola.
            let xi_min = match (&o.shape, o.kind) {
                (Shape::Mesh(m), renderer::ObjectKind::VObj) => m
                    .vertices
                    .iter()
                    .map(|v| v.dot(h.direction))
                    .fold(0.0, f64::min),
                _ => 0.0,
            };
            // A Born-rigid body's cut in time takes half the tolerance.
            let share = match o.kind {
                renderer::ObjectKind::VObj => 0.5,
                renderer::ObjectKind::HObj => 1.0,
            };
            let a_min = 1.0 / h.acceleration + xi_min;
            let step = (8.0 * share * h.tolerance * a_min).sqrt();
            let n = (h.duration / step).ceil();
            if n.is_finite() && n >= 1.0 {
                (n as u64).min(MAX_HYPERBOLIC_INTERVALS)
            } else {
                MAX_HYPERBOLIC_INTERVALS
            }
        }
        Motion::Extrusion { .. } | Motion::Velocity { .. } => 1,
    }
}

/// A byte count as a person reads it.
struct Bytes(u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.0 as f64;
        if b >= 1e9 {
            write!(f, "{:.1} GB", b / 1e9)
        } else {
            write!(f, "{:.0} MB", b / 1e6)
        }
    }
}

/// A duration as a person reads it.
struct Seconds(f64);

impl fmt::Display for Seconds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.0;
        if s >= 86_400.0 {
            write!(f, "{:.1} days", s / 86_400.0)
        } else if s >= 3600.0 {
            write!(f, "{:.1} hours", s / 3600.0)
        } else {
            write!(f, "{s:.0} s")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_day_of_rendering_is_refused_with_its_estimate_and_an_hour_is_not() {
        let e = Budget::DEFAULT
            .check_work((8192, 8192), 4096, 1)
            .unwrap_err();
        assert!(
            matches!(&e, Error::Budget { message }
                if message.contains("days") && message.contains("--force")),
            "{e}"
        );
        Budget::DEFAULT.check_work((8192, 8192), 1, 1).unwrap();
        Budget::DEFAULT.check_work((640, 480), 4096, 1).unwrap();
        Budget::UNLIMITED.check_work((8192, 8192), 4096, 1).unwrap();
    }
}
