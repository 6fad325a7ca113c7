//! The triangles of translations at rest in their stretches' comoving
//! coordinates, kept as indexed meshes: each run's vertices once, and its
//! triangles as corner indices in the order the run's hierarchy holds them
//! (24 bytes a vertex and 12 a triangle, where three f64 corners would take
//! 72 bytes a triangle).

use glam::DVec3;

/// Triangles from which [`ComovingMeshes::read_ahead`] asks ahead: their
/// indices (12 bytes each) fill 3 MB, more than a core's cache below the
/// last level on the machines measured (docs/performance.md).
const READ_AHEAD_FROM: usize = 1 << 18;

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

    /// Asks for the corner indices of the triangles stored at positions
    /// `first..end` (side by side: a cache line or two) without waiting for
    /// them, so that their fetch from memory overlaps the work before their
    /// first use (the f32 filter's, in a leaf). Only where there are enough
    /// triangles that their indices are likely out of cache.
    #[inline(always)]
    pub(super) fn read_ahead(&self, first: usize, end: usize) {
        if self.corners.len() < READ_AHEAD_FROM {
            return;
        }
        let leaf = self.corners.get(first..end).unwrap_or_default();
        if let (Some(a), Some(b)) = (leaf.first(), leaf.last()) {
            fetch(a);
            fetch(&b[2]);
        }
    }
}

/// Asks for the cache line holding `value`'s first byte in every cache
/// level (x86's `prefetcht0`, through `safe_arch`'s safe wrapper): a hint
/// that neither waits nor faults, and changes no result.
#[inline(always)]
fn fetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    safe_arch::prefetch_t0(value);
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reading ahead stays inside the stored triangles whatever the range
    /// (an empty leaf, one past the end, one reaching over it), in a
    /// database large enough to read ahead in and in one too small to.
    #[test]
    fn reading_ahead_stays_inside_the_triangles() {
        for len in [READ_AHEAD_FROM - 1, READ_AHEAD_FROM] {
            let meshes = ComovingMeshes {
                vertices: vec![DVec3::ZERO],
                corners: vec![[0; 3]; len],
            };
            for (first, end) in [
                (0, 0),
                (5, 5),
                (len - 2, len),
                (len, len + 3),
                (len - 1, len + 4),
            ] {
                meshes.read_ahead(first, end);
            }
        }
    }
}
