//! Hyperbolic motion resolved into poses: objects on one worldline share
//! their cut in lab time and the levels that cut a Born-rigid surface, so
//! that where their meshes meet the shared edges stay closed.

use crate::geometry::{Pieces, Pose};
use crate::scene::{Fault, Hyperbolic, Mesh, Motion, ObjectKind, Scene, SceneObject};

/// What the objects on one worldline, moving the same way (Born-rigid or
/// not), share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Shared {
    /// The most intervals any of them needs (0 when none can be cut).
    pub(super) cut: usize,
    /// The finest valid tolerance among them.
    pub(super) tolerance: f64,
}

/// A hyperbolic object's surface and path: the mesh its prisms are made of
/// (the given one, or the cut of a Born-rigid one), the given triangle each
/// of its triangles lies in (empty: itself), and the poses.
pub(super) struct Resolved {
    pub(super) pieces: Option<Pieces>,
    pub(super) poses: Vec<Pose>,
}

impl Resolved {
    /// The mesh the prisms are made of.
    pub(super) fn mesh<'m>(&'m self, given: &'m Mesh) -> &'m Mesh {
        self.pieces.as_ref().map_or(given, |p| &p.mesh)
    }

    /// The given triangle of each triangle of [`Resolved::mesh`] (empty:
    /// the same).
    pub(super) fn parents(&self) -> &[u32] {
        self.pieces.as_ref().map_or(&[], |p| &p.parents)
    }
}

/// The poses of `mesh` under `h`, cut at least `shared.cut` times; a
/// Born-rigid mesh is first cut into pieces flat within half the finest
/// tolerance on the worldline (the cut in time takes the other half of
/// each object's own).
pub(super) fn resolve_hyperbolic(
    h: &Hyperbolic,
    mesh: &Mesh,
    born_rigid: bool,
    shared: Option<Shared>,
) -> Result<Resolved, Fault> {
    let own = h.intervals(mesh, born_rigid)?;
    let cut = own.max(shared.map_or(0, |s| s.cut));
    let pieces = if born_rigid {
        let finest = shared.map_or(h.tolerance, |s| s.tolerance.min(h.tolerance));
        Some(h.born_rigid_pieces(mesh, 0.5 * finest)?)
    } else {
        None
    };
    let poses = h.poses_in(pieces.as_ref().map_or(mesh, |p| &p.mesh), born_rigid, cut)?;
    Ok(Resolved { pieces, poses })
}

/// For each object in hyperbolic motion, what the objects on the same
/// worldline, moving the same way, share: all of them are cut at the same
/// lab times, so that where their meshes meet (a cube of six faces as six
/// objects) the shared vertices, on the same hyperbolae, are interpolated
/// between the same events; and a Born-rigid surface is cut at the same
/// levels, so a shared edge is split at the same points. An object whose
/// own cut fails is left to report its error.
pub(super) fn shared_cuts(
    scene: &Scene,
    lorentz: bool,
    mesh_of: impl Fn(&SceneObject) -> &Mesh,
) -> Vec<Option<Shared>> {
    let motion = |obj: &SceneObject| match &obj.motion {
        Motion::Hyperbolic(h) => Some((*h, lorentz && obj.kind == ObjectKind::VObj)),
        _ => None,
    };
    let own: Vec<Option<usize>> = scene
        .objects
        .iter()
        .map(|obj| {
            let (h, born_rigid) = motion(obj)?;
            h.intervals(mesh_of(obj), born_rigid).ok()
        })
        .collect();
    scene
        .objects
        .iter()
        .map(|obj| {
            let (h, born_rigid) = motion(obj)?;
            let group = || {
                scene.objects.iter().zip(&own).filter_map(|(other, n)| {
                    let (g, b) = motion(other)?;
                    (b == born_rigid && h.same_worldline(&g)).then_some((g, *n))
                })
            };
            Some(Shared {
                cut: group().filter_map(|(_, n)| n).max().unwrap_or(0),
                tolerance: group()
                    .map(|(g, _)| g.tolerance)
                    .filter(|t| *t > 0.0 && t.is_finite())
                    .fold(f64::INFINITY, f64::min),
            })
        })
        .collect()
}
