//! The triangles of translations at rest in their stretches' comoving
//! coordinates, kept as indexed meshes: each run's vertices once, and its
//! triangles as corner indices in the order the run's hierarchy holds them
//! (24 bytes a vertex and 12 a triangle, where three f64 corners would take
//! 72 bytes a triangle).

use glam::DVec3;

/// Every translation's comoving triangles, run after run.
#[derive(Debug, Default)]
pub(super) struct ComovingMeshes {
    /// Each run's vertices, from the run's `vertices` on.
    pub(super) vertices: Vec<DVec3>,
    /// Each triangle's corners, by index among its run's vertices: a run's
    /// triangles from its `slot` on, in leaf order.
    pub(super) corners: Vec<[u32; 3]>,
}

impl ComovingMeshes {
    /// How many triangles there are.
    pub(super) fn len(&self) -> usize {
        self.corners.len()
    }

    /// The triangle stored at position `j`, of a run whose vertices start
    /// at `base`.
    #[inline(always)]
    pub(super) fn triangle(&self, base: usize, j: usize) -> [DVec3; 3] {
        self.corners[j].map(|i| self.vertices[base + i as usize])
    }
}
