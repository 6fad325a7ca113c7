//! Recording the variables along a ray: the VSTF's debug mode (paper
//! section 4: "a means to interactively examine variables or to log results
//! for later comparison").
//!
//! The renderer's own functions take a [`Trace`]; rendering passes
//! [`NoTrace`], whose recording compiles away, and the debug command passes a
//! [`Recorder`]. There is no second implementation of the physics to drift.

use crate::geometry::{Barycentric, Hit, Miss, PrimitiveId};
use crate::spacetime::{Event, FourVector};
use glam::DVec3;
#[cfg(feature = "serde")]
use serde::Serialize;

/// What a ray is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum RayKind {
    /// From the camera.
    Primary,
    /// From a hit towards the light.
    Shadow,
    /// From a mirror hit along the reflected direction.
    Reflection,
}

/// The outcome of one test of a prism (whole, as its comoving triangle) or
/// of a tetrahedron (the barycentric solve).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "result", rename_all = "snake_case"))]
pub enum Outcome {
    /// The ray meets the primitive.
    Accepted {
        /// Ray parameter.
        s: f64,
        /// The event met.
        event: Event,
        /// Its barycentric coordinates, clamped to [0, 1].
        bary: Barycentric,
    },
    /// The ray is parallel to the tetrahedron's hyperplane (lies in the
    /// plane of the prism's comoving triangle).
    Parallel,
    /// The hyperplane (the triangle's plane) is met outside the searched
    /// stretch of the ray (behind the origin, or beyond a hit already found).
    OutOfRange {
        /// Ray parameter where the hyperplane is met.
        s: f64,
    },
    /// The hyperplane (the triangle's plane) is met outside the primitive.
    Outside {
        /// Ray parameter where the hyperplane is met.
        s: f64,
        /// Barycentric coordinates there, one of them negative.
        bary: Barycentric,
    },
    /// The prism's triangle is crossed before or after the prism's lab times.
    OutOfSpan {
        /// Ray parameter of the crossing.
        s: f64,
        /// Its lab time.
        t: f64,
    },
}

impl From<&Result<Hit, Miss>> for Outcome {
    fn from(r: &Result<Hit, Miss>) -> Outcome {
        match *r {
            Ok(h) => Outcome::Accepted {
                s: h.s,
                event: h.event,
                bary: h.bary,
            },
            Err(Miss::Parallel) => Outcome::Parallel,
            Err(Miss::OutOfRange { s }) => Outcome::OutOfRange { s },
            Err(Miss::Outside { s, bary }) => Outcome::Outside { s, bary },
            Err(Miss::OutOfSpan { s, t }) => Outcome::OutOfSpan { s, t },
        }
    }
}

/// One recorded step.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "step", rename_all = "snake_case"))]
pub enum Step {
    /// A sample of the pixel: where in the pixel and at which camera time.
    Sample {
        /// Sample number within the pixel.
        index: u32,
        /// Continuous pixel position, x.
        px: f64,
        /// Continuous pixel position, y.
        py: f64,
        /// Camera time of the sample, t.units.
        camera_t: f64,
    },
    /// A ray about to be searched.
    Ray {
        /// What the ray is for.
        kind: RayKind,
        /// Mirror bounces before this ray.
        depth: u32,
        /// The event the ray starts from.
        origin: Event,
        /// Spatial part a unit vector; t = -1 on a light cone, 0 for infinite light speed.
        direction: FourVector,
        /// The same direction with unit Euclidean length in 4D (t = -sqrt(2)/2 on a light cone).
        normalized: FourVector,
        /// Searched range of the ray parameter.
        range: (f64, f64),
    },
    /// A prism (whole) or tetrahedron tested against the current ray.
    Candidate {
        /// The primitive tested.
        primitive: PrimitiveId,
        /// Name of the object.
        object: String,
        /// Index of the triangle in the object's mesh.
        triangle: u32,
        /// Index of the prism (the one tested, or the tetrahedron's).
        prism: u32,
        /// The result of the test.
        outcome: Outcome,
    },
    /// The hit kept for the current ray (the most recent event), or the first
    /// blocker of a shadow ray.
    Hit {
        /// What the ray is for.
        kind: RayKind,
        /// The primitive met.
        primitive: PrimitiveId,
        /// Name of the object.
        object: String,
        /// Index of the triangle in the object's mesh (0 for a sphere).
        triangle: u32,
        /// Where the ray meets it.
        event: Event,
        /// The hit in the object's frame: rest-frame offset from its reference point.
        surface_point: DVec3,
        /// The object's own time at the hit, counted from its start.
        proper_time: f64,
        /// Lab time of the object's start (its first stretch's), from which
        /// its own time counts.
        start_t: f64,
        /// Lab-frame unit normal of the triangle, and the same turned to the side seen.
        normal: DVec3,
        /// The normal turned to the side the ray's origin sees: in the
        /// surface's frame when it moves (`Shader::facing_normal`).
        facing_normal: DVec3,
    },
    /// The current ray met nothing.
    Miss {
        /// What the ray was for.
        kind: RayKind,
        /// The background colour returned.
        background: DVec3,
    },
    /// The shading terms at a hit.
    Shading {
        /// Mirror bounces before this ray.
        depth: u32,
        /// Material colour at the object's proper time.
        albedo: DVec3,
        /// Ambient term.
        ambient: DVec3,
        /// Unit vector from the hit towards the light, and the distance.
        light_vector: DVec3,
        /// Distance to the light, l.units.
        light_distance: f64,
        /// n . l with the facing normal (in the surface's frame when it moves).
        lambert: f64,
        /// A moving surface's facing normal, and the directions towards
        /// the light and towards the viewer, in its own frame.
        surface_frame: Option<[DVec3; 3]>,
        /// Whether the light is hidden.
        in_shadow: bool,
        /// Lambert term.
        diffuse: DVec3,
        /// Phong term.
        specular: f64,
        /// Mirror fraction of the material.
        mirror: f64,
        /// Colour before the mirror term, and the colour returned.
        local: DVec3,
        /// Colour returned.
        color: DVec3,
    },
    /// The colour effects of the surface's motion at a hit (with
    /// `--doppler` or `--searchlight`). Frequency ratios are 1 when off.
    Doppler {
        /// Mirror bounces before this ray.
        depth: u32,
        /// Lab velocity of the surface, and its clock's gamma (1:
        /// classical Doppler).
        surface_velocity: DVec3,
        /// Gamma of the surface's clock.
        gamma: f64,
        /// nu_surface / nu_lab of the light arriving from the lamp.
        from_light: f64,
        /// nu_lab / nu_surface of the light leaving towards the ray's
        /// origin: the surface's Doppler factor D.
        to_origin: f64,
        /// nu_surface / nu_lab of the light arriving along the mirror ray.
        from_mirror: Option<f64>,
        /// With Doppler: the band's wavelengths in the surface's frame, nm,
        /// and the spectral radiance leaving the surface there.
        surface_nm: Option<Vec<f64>>,
        /// Spectral radiance leaving the surface, at those wavelengths.
        surface_radiance: Option<Vec<f64>>,
    },
    /// A moving mirror's reflection at a hit, by the law in its rest frame.
    Reflection {
        /// Mirror bounces before this ray.
        depth: u32,
        /// Lab velocity of the mirror's surface at the hit.
        mirror_velocity: DVec3,
        /// Lab unit direction of the photon leaving the mirror (towards the
        /// ray's origin), and of the one it reflected.
        k_out: DVec3,
        /// Lab unit direction of the incident photon.
        k_in: DVec3,
        /// nu_out / nu_in in the lab: the double Doppler factor.
        frequency_ratio: f64,
        /// In the mirror's rest frame, where it has one: the unit normal,
        /// and the outgoing and incident directions.
        rest_frame: Option<[DVec3; 3]>,
    },
    /// The gravitational shift of the light a bent primary ray brings to
    /// the camera (with `--doppler` or `--searchlight` in a mass's field).
    Gravitational {
        /// Distance from the mass of the static emitter (infinite for the
        /// background), and of the camera, l.units.
        emitter_r: f64,
        /// Distance from the mass of the camera.
        observer_r: f64,
        /// nu at the camera's static observer / nu at the emitter's:
        /// sqrt((1 - 2M/r_e) / (1 - 2M/r_o)).
        factor: f64,
    },
    /// What the camera records for the sample (with `--doppler` or
    /// `--searchlight`).
    Observed {
        /// nu_camera / nu_lab along the primary ray.
        doppler: f64,
        /// With Doppler: the lab wavelengths of the observed band, nm, and
        /// the CIE XYZ of the observed spectrum.
        lab_nm: Option<Vec<f64>>,
        /// CIE XYZ of the observed spectrum.
        xyz: Option<DVec3>,
        /// Linear sRGB.
        color: DVec3,
    },
}

/// A sink for recorded steps.
pub trait Trace {
    /// Whether anything is recorded: when false, callers skip building steps.
    const ENABLED: bool;
    /// Keeps one step.
    fn record(&mut self, step: Step);
}

/// Records nothing (rendering).
pub struct NoTrace;

impl Trace for NoTrace {
    const ENABLED: bool = false;
    #[inline(always)]
    fn record(&mut self, _: Step) {}
}

/// Records every step, in order (debugging).
#[derive(Default, Debug)]
pub struct Recorder {
    /// The steps recorded, in order.
    pub steps: Vec<Step>,
}

impl Trace for Recorder {
    const ENABLED: bool = true;
    fn record(&mut self, step: Step) {
        self.steps.push(step);
    }
}
