//! The texture colour at a hit: the surface point in its object's own frame
//! and, on a mesh, its place in the triangle hit.

use super::shader::Shader;
use crate::database::{ObjectRecord, Surface};
use crate::geometry::{Barycentric, Hit};
use crate::scene::SurfacePoint;
use glam::DVec3;

impl Shader<'_> {
    /// The texture colour at `hit` on `object` (whose `surface` it is), or
    /// `None` for an untextured material. The point is taken back to the
    /// object's rest frame (`ObjectRecord::local_point`), where the texture
    /// is painted. Mesh coordinates come from the hit's barycentric weights
    /// over its triangle, known for a uniformly moving mesh; a keyframe
    /// interval's tetrahedron gives none, and an image shows the base
    /// colour there.
    pub(super) fn texel(
        &self,
        hit: &Hit,
        surface: &Surface,
        object: &ObjectRecord,
    ) -> Option<DVec3> {
        let m = object.material_of(surface.triangle);
        let texture = m.texture.as_ref()?;
        let corners = match hit.bary {
            Barycentric::Triangle(b) => Some((surface.triangle, b)),
            Barycentric::Tetrahedron(_) | Barycentric::Sphere => None,
        };
        let point = SurfacePoint {
            local: object.local_point(hit.event),
            corners,
        };
        texture.color(m.color, &point)
    }
}
