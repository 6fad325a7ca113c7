//! An object as inserted: its path as straight stretches with their clocks.

use crate::scene::{Material, ObjectKind};
use crate::spacetime::{Boost, Event, Worldline};
use glam::DVec3;

/// One straight stretch of an object's path: its whole worldline for
/// uniform motion, or the interval between two consecutive poses of
/// keyframed or accelerated motion. The unit of the object's path
/// everywhere: its clock, its prisms, and one hierarchy of the two-level
/// acceleration structure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    /// Lab-frame worldline of the reference point over the stretch.
    pub worldline: Worldline,
    /// Boost from the stretch's comoving frame (identity when
    /// Lorentz-decoupled).
    pub clock: Boost,
    /// The object's proper time at the start of the stretch.
    pub proper_start: f64,
    /// Whether every point of the object moves with the reference point
    /// over the stretch (uniform motion); false for a keyframe interval,
    /// which may turn or deform the mesh.
    pub translation: bool,
}

/// An object as inserted into the database.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectRecord {
    /// The object's name in the scene.
    pub name: String,
    /// Whether it was given as an H_obj or a V_obj.
    pub kind: ObjectKind,
    /// Its surface appearance: material 0.
    pub material: Material,
    /// Its materials 1, 2, ... ([`crate::SceneObject::face_materials`]).
    pub face_materials: Vec<Material>,
    /// The material index of each triangle of its mesh; empty when all are
    /// of material 0 ([`crate::Mesh::materials`]).
    pub triangle_materials: Vec<u32>,
    /// Whether it was inserted Lorentz-transformed (a V_obj with the
    /// transform on): its points' clocks run at the gamma of their speed.
    pub contracted: bool,
    /// Its path in lab-time order: one stretch for uniform motion, one per
    /// interval between poses otherwise.
    pub stretches: Vec<Stretch>,
    /// Each material's [`Material::emission_rgb`] (material 0 first),
    /// integrated once rather than at every hit.
    pub(super) emission_rgb: Vec<Option<DVec3>>,
}

impl ObjectRecord {
    /// The material of triangle `triangle` of the object's mesh (of the
    /// object, for an analytic sphere).
    pub fn material_of(&self, triangle: u32) -> &Material {
        match self.material_index(triangle) {
            0 => &self.material,
            k => &self.face_materials[k - 1],
        }
    }

    /// [`Material::emission_rgb`] of the material of triangle `triangle`.
    pub fn emission_rgb_of(&self, triangle: u32) -> Option<DVec3> {
        self.emission_rgb[self.material_index(triangle)]
    }

    /// The index of triangle `triangle`'s material: 0 for the object's own.
    fn material_index(&self, triangle: u32) -> usize {
        match self.triangle_materials.get(triangle as usize) {
            Some(&k) => k as usize,
            None => 0,
        }
    }

    /// The stretch of the path at lab time `t` (the first or last outside
    /// the lifetime).
    pub fn stretch_at(&self, t: f64) -> &Stretch {
        let k = self.stretches.partition_point(|p| p.worldline.end().t < t);
        &self.stretches[k.min(self.stretches.len() - 1)]
    }

    /// Lab times of the start and end of the object's existence.
    pub fn lifetime(&self) -> (f64, f64) {
        let (first, last) = (self.stretches[0], self.stretches[self.stretches.len() - 1]);
        (first.worldline.start.t, last.worldline.end().t)
    }

    /// The object's own time at a lab event on it: the comoving frame's
    /// time coordinate, zero at the start event; for a decoupled object, lab
    /// time since the start. Drives time-dependent materials (paper 3,
    /// item 2d).
    pub fn proper_time(&self, event: Event) -> f64 {
        let p = self.stretch_at(event.t);
        p.proper_start + p.clock.to_rest(event - p.worldline.start).t
    }

    /// Where a lab event on the object lies in the object's frame: its
    /// comoving position relative to the reference point, in lab axes.
    /// The reference point is at rest at the origin of the comoving frame,
    /// so the event is first taken relative to the reference point at the
    /// same lab time, then boosted: x' = Boost^-1 (event - reference(t)).x,
    /// which for a Lorentz-decoupled object is x - x_ref(t) itself. For a
    /// V_obj the rest-frame (uncontracted) offset follows.
    pub fn local_point(&self, event: Event) -> DVec3 {
        let p = self.stretch_at(event.t);
        let reference = Event::new(event.t, p.worldline.position_at(event.t));
        p.clock.to_rest(event - reference).x
    }
}

#[cfg(test)]
mod tests {
    use crate::database::tests::{object, scene};
    use crate::database::Database;
    use crate::scene::{Material, Mesh, Motion, ObjectKind, Shape};
    use crate::spacetime::{Event, FourVector};
    use glam::DVec3;

    /// A point of a moving object is where it is in the object's own frame,
    /// whatever the lab time: for a vertex at rest-frame offset p of a cube at
    /// 0.6c, `local_point` of the vertex's lab event at any time is p, with and
    /// without the Lorentz transform. (Position minus start position would
    /// grow by v t: the negative control.)
    #[test]
    fn a_vertex_stays_at_its_offset_in_the_objects_frame() {
        let v = DVec3::new(0.6, 0.0, 0.0);
        let gamma = 1.0 / (1.0 - v.length_squared()).sqrt();
        let start = Event::new(-10.0, DVec3::new(-4.0, 0.5, -3.0));
        let motion = Motion::Extrusion {
            start,
            extrusion: FourVector::new(20.0, v * 20.0),
        };
        let mesh = Mesh::cuboid(DVec3::splat(-1.0), DVec3::new(1.0, 2.0, 1.5));
        for (kind, lorentz) in [
            (ObjectKind::HObj, true),
            (ObjectKind::VObj, true),
            (ObjectKind::VObj, false),
        ] {
            let contracted = kind == ObjectKind::VObj && lorentz;
            let s = scene(vec![object("cube", kind, mesh.clone(), motion.clone())]);
            let db = Database::build(&s, lorentz).unwrap();
            let record = &db.objects()[0];
            for &p in &mesh.vertices {
                for t in [-8.0, 0.0, 7.5] {
                    let lab = if contracted {
                        DVec3::new(p.x / gamma, p.y, p.z)
                    } else {
                        p
                    };
                    let event = Event::new(t, start.x + v * (t - start.t) + lab);
                    let local = record.local_point(event);
                    assert!(
                        (local - p).length() < 1e-12,
                        "{kind:?} lorentz {lorentz}: vertex {p} at t = {t} shows as {local}"
                    );
                    let naive = event.x - start.x;
                    assert!((naive - p).length() > 0.5, "the control does not move");
                }
            }
        }
    }

    /// Each triangle takes the material its index names (0: the object's
    /// own), and an index naming no material, or a list not one per
    /// triangle, is refused at insertion.
    #[test]
    fn triangles_take_the_material_they_name() {
        let motion = Motion::at_rest(DVec3::ZERO, -1.0, 1.0);
        let mut mesh = Mesh::cuboid(DVec3::splat(-1.0), DVec3::ONE);
        mesh.materials = vec![0, 0, 1, 1, 2, 2, 0, 0, 0, 0, 0, 0];
        let mut o = object("cube", ObjectKind::HObj, mesh, motion);
        o.face_materials = vec![Material::matte(DVec3::X), Material::matte(DVec3::Y)];
        let db = Database::build(&scene(vec![o.clone()]), false).unwrap();
        let r = &db.objects()[0];
        let colours: Vec<DVec3> = (0..12).map(|t| r.material_of(t).color).collect();
        assert_eq!(colours[0], DVec3::new(0.8, 0.5, 0.2));
        assert_eq!(
            (colours[2], colours[3], colours[5]),
            (DVec3::X, DVec3::X, DVec3::Y)
        );
        o.face_materials.pop();
        let Err(e) = Database::build(&scene(vec![o.clone()]), false) else {
            panic!("an index naming no material was accepted")
        };
        assert_eq!(
            e.kind,
            crate::SceneErrorKind::MaterialIndex {
                triangle: 4,
                index: 2,
                materials: 2
            }
        );
        let Shape::Mesh(m) = &mut o.shape else {
            unreachable!()
        };
        m.materials.pop();
        let Err(e) = Database::build(&scene(vec![o]), false) else {
            panic!("11 indices for 12 triangles were accepted")
        };
        assert!(matches!(
            e.kind,
            crate::SceneErrorKind::Mesh(crate::MeshError::MaterialCount {
                materials: 11,
                triangles: 12
            })
        ));
    }
}
