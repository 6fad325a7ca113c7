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
    /// Its surface appearance.
    pub material: Material,
    /// Whether it was inserted Lorentz-transformed (a V_obj with the
    /// transform on): its points' clocks run at the gamma of their speed.
    pub contracted: bool,
    /// Its path in lab-time order: one stretch for uniform motion, one per
    /// interval between poses otherwise.
    pub stretches: Vec<Stretch>,
}

impl ObjectRecord {
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
