//! Curved spacetime: the field of a mass at rest in the lab (Schwarzschild),
//! and light's null geodesics through it, cut into straight 4D chords that
//! the flat database searches one after another.
//!
//! Coordinates are Schwarzschild's (t, r, theta, phi) around the mass's
//! centre, written as lab x, y, z = centre + r (unit direction): far from
//! the mass they are the lab's. A null geodesic stays in the plane of its
//! start and its direction; in that plane its orbit u(phi) = 1/r obeys
//! u'' = 3 M u^2 - u exactly. That orbit is the path of a point pushed by
//! the central acceleration a = -3 M h^2 x / r^5, h = |x cross v| (Binet's
//! equation of the orbit under a central force: u'' + u = -F / (h^2 u^2)),
//! for any starting speed, which is what is integrated here in the lab's
//! Cartesian form (no pole in the plane; a radial ray has h = 0 and runs
//! straight, as the radial null geodesic does). Coordinate time follows
//! from the null condition: (1 - 2M/r) dt^2 = dr^2 / (1 - 2M/r) + r^2 dOmega^2.

use super::{Event, FourVector, LightSpeed, Ray};
use glam::DVec3;
use stepping::CLEAR_STEP;

/// The spacetime light travels through.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Spacetime {
    /// Special relativity: every ray is one straight line.
    #[default]
    Flat,
    /// The field of one mass at rest in the lab.
    Schwarzschild(Schwarzschild),
}

impl Spacetime {
    /// The field of `mass` (l.units: M = G m / c^2) centred on `centre`;
    /// flat when the mass is 0.
    pub fn of_mass(mass: f64, centre: DVec3) -> Spacetime {
        if mass == 0.0 {
            Spacetime::Flat
        } else {
            Spacetime::Schwarzschild(Schwarzschild { mass, centre })
        }
    }
}

/// A mass at rest in the lab, its field outside its horizon r = 2M.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schwarzschild {
    /// M = G m / c^2, l.units (the horizon's radius is 2M).
    pub mass: f64,
    /// Where it is, lab coordinates.
    pub centre: DVec3,
}

impl Schwarzschild {
    /// f(r) = 1 - 2M/r = -g_tt at the lab point `x`: the square of the rate
    /// of a static clock there against coordinate time.
    pub fn lapse_squared(&self, x: DVec3) -> f64 {
        1.0 - 2.0 * self.mass / (x - self.centre).length()
    }

    /// nu_observer / nu_emitter for light from an emitter at rest at
    /// `emitter` to an observer at rest at `observer` (gravitational
    /// redshift): sqrt(f(r_e) / f(r_o)), whatever path the light took, as
    /// E = -k_t is conserved along every geodesic and a static observer
    /// measures E / sqrt(f). 0 for an emitter on or inside the horizon.
    pub fn static_shift(&self, emitter: DVec3, observer: DVec3) -> f64 {
        let (fe, fo) = (self.lapse_squared(emitter), self.lapse_squared(observer));
        if fe <= 0.0 {
            return 0.0;
        }
        (fe / fo).sqrt()
    }

    /// A point's coordinate velocity `velocity` (dx/dt) and light's
    /// coordinate direction `k` at the lab point `x`, as the observer at
    /// rest there measures them in its orthonormal frame (proper length
    /// dr / sqrt(f) radially, r dOmega across; proper time sqrt(f) dt):
    /// the velocity's radial part divided by f and its transverse part by
    /// sqrt(f); the light's radial part divided by sqrt(f), the direction
    /// then normalised.
    pub fn static_frame(&self, x: DVec3, velocity: DVec3, k: DVec3) -> (DVec3, DVec3) {
        let radial = (x - self.centre).normalize();
        let f = self.lapse_squared(x);
        let rs = f.sqrt();
        let split = |w: DVec3| {
            let along = radial * w.dot(radial);
            (along, w - along)
        };
        let (vr, vt) = split(velocity);
        let (kr, kt) = split(k);
        (vr / f + vt / rs, (kr / rs + kt).normalize())
    }
}

/// The most a chord strays from its geodesic, in units of M, wherever the
/// pixel's footprint is finer: no point of a chord is farther than
/// `CHORD_TOLERANCE * M` in space, nor in coordinate time, from the
/// geodesic's point at the same fraction of its arc.
pub const CHORD_TOLERANCE: f64 = 1e-3;

/// Beyond the camera's surroundings a chord may stray from its geodesic by
/// this fraction of the pixel's footprint there (the pixel's angle times
/// the arc travelled from the camera): a hit is found where the object
/// would be if it were moved by at most that much.
pub const PIXEL_FRACTION: f64 = 1.0 / 8.0;

/// A ray still bound after this many chords (circling near the photon
/// sphere r = 3M, each turn dimming its light by e^(2 pi)) is taken as
/// captured.
pub const MAX_CHORDS: usize = 20_000;

/// Where a light ray's coordinate distance from the mass is measured from,
/// beyond which no geometry is searched as curved: `FAR_FACTOR` times the
/// camera's distance (geometry farther still is met on a straight last chord).
const FAR_FACTOR: f64 = 1e6;

/// The most an escaping ray's direction may still turn beyond the point at
/// which [`Geodesic::asymptote`] reads it, radians.
pub const SKY_TOLERANCE: f64 = 1e-6;

/// One leg of a geodesic traced backwards from its camera event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Leg {
    /// A straight chord: its ray (origin at the chord's later event, the
    /// direction's spatial part a unit vector, its time part the chord's
    /// coordinate time per unit length) and its length; the last chord of
    /// an escaping ray is infinite.
    Chord(Ray, f64),
    /// The light came out of the hole: the ray crossed the photon sphere
    /// inwards (every such null geodesic reaches the horizon), or stayed
    /// bound past [`MAX_CHORDS`].
    Captured,
}

/// A null geodesic traced backwards from an event, chord by chord.
pub struct Geodesic {
    mass: f64,
    centre: DVec3,
    /// Position relative to the centre, and d/d(lambda) of it.
    x: DVec3,
    v: DVec3,
    /// Coordinate time.
    t: f64,
    /// -1 when light takes time (c = 1), 0 when it is instantaneous.
    time_sign: f64,
    /// Outgoing beyond this radius, the ray meets no geometry bent.
    far: f64,
    /// The coordinate length travelled from the camera.
    arc: f64,
    /// The angle a pixel subtends, radians (0: the tolerance in M alone).
    pixel_angle: f64,
    /// The least and greatest corners of a box, relative to the centre,
    /// holding every object at every time (everywhere unless told).
    geometry: (DVec3, DVec3),
    /// The fraction of the radius the next step clear of every object
    /// tries, adapted to its error.
    clear_fraction: f64,
    /// The last chord given passes clear of every object.
    cleared: bool,
    chords: usize,
    done: bool,
    /// The last, infinite chord has been given.
    escaped: bool,
}

impl Geodesic {
    /// The null geodesic along which light reaches `origin` from the
    /// direction `towards` (a unit vector in the frame of an observer at
    /// rest there, whose radial lengths are dr / sqrt(1 - 2M/r)), traced
    /// backwards; `reach` bounds the distance from the centre of all
    /// geometry.
    pub fn backwards(
        s: &Schwarzschild,
        origin: Event,
        towards: DVec3,
        light: LightSpeed,
        reach: f64,
    ) -> Geodesic {
        let x = origin.x - s.centre;
        let r = x.length();
        let f = 1.0 - 2.0 * s.mass / r;
        let v = if r > 0.0 && f > 0.0 {
            let radial = x / r;
            let nr = towards.dot(radial);
            (towards + radial * (nr * (f.sqrt() - 1.0))).normalize()
        } else {
            towards
        };
        let time_sign = match light {
            LightSpeed::Finite => -1.0,
            LightSpeed::Infinite => 0.0,
        };
        Geodesic {
            mass: s.mass,
            centre: s.centre,
            x,
            v,
            t: origin.t,
            time_sign,
            far: reach.min(FAR_FACTOR * r).max(3.0 * s.mass),
            arc: 0.0,
            pixel_angle: 0.0,
            geometry: (DVec3::NEG_INFINITY, DVec3::INFINITY),
            clear_fraction: CLEAR_STEP,
            cleared: false,
            chords: 0,
            escaped: false,
            done: !(r.is_finite() && v.is_finite()),
        }
    }

    /// The same geodesic, its chords allowed to stray by `PIXEL_FRACTION`
    /// of the footprint of a pixel subtending `angle` radians (in the
    /// lab's coordinates at the camera), where that is more than
    /// [`CHORD_TOLERANCE`] M.
    pub fn sized_to_pixel(self, angle: f64) -> Geodesic {
        Geodesic {
            pixel_angle: angle.max(0.0),
            ..self
        }
    }

    /// The same geodesic told that every object lies, at every time, in
    /// the box from `lo` to `hi` (lab coordinates): where it passes clear
    /// of that box its steps are as long as `CLEAR_STEP` and
    /// `CLEAR_TURN` allow, however far their chords stray.
    pub fn with_geometry_in(self, lo: DVec3, hi: DVec3) -> Geodesic {
        Geodesic {
            geometry: (lo - self.centre, hi - self.centre),
            ..self
        }
    }

    /// Whether the last chord given passes clear of every object (told by
    /// [`Geodesic::with_geometry_in`]), so that no search along it can meet
    /// anything.
    pub fn passed_clear(&self) -> bool {
        self.cleared
    }
}

impl Geodesic {
    /// The direction (a lab unit vector) the light came from at infinity,
    /// once the geodesic has given its last, infinite chord: the chord
    /// leaves where the ray has passed all geometry, where its direction
    /// may still turn by up to 2M/r, so the orbit is followed further out,
    /// chord by chord, until what is left is within [`SKY_TOLERANCE`]. The
    /// path in these coordinates curves by kappa = 3 M sin^3(psi) / r^2 per
    /// unit length (psi between it and the radius; [`Geodesic`]), so on the
    /// nearly straight rest of the way out, of impact parameter
    /// b = r sin(psi), it turns by at most the integral of 3 M b^3 / (s^2 +
    /// b^2)^(5/2) beyond s = r cos(psi): (M / b) (1 - cos psi)^2 (2 + cos psi).
    /// `None` for a ray that was captured or has not yet escaped.
    pub fn asymptote(&mut self) -> Option<DVec3> {
        let m = self.mass;
        for _ in 0..MAX_CHORDS {
            let r = self.x.length();
            let speed = self.v.length();
            let c = (self.x.dot(self.v) / (r * speed)).min(1.0);
            if !(self.escaped && c >= 0.0) {
                return None;
            }
            let left = m * (2.0 + c) * (1.0 - c) * ((1.0 - c) / (1.0 + c)).sqrt() / r;
            if left <= SKY_TOLERANCE {
                return Some(self.v / speed);
            }
            if self.step() == Leg::Captured {
                return None;
            }
        }
        None
    }
}

/// How a geodesic's next leg comes.
enum Next {
    /// From a step of its integration.
    Step,
    /// Without one: none after the last, captured, or the last, infinite
    /// chord of an escaping ray.
    Given(Option<Leg>),
}

impl Iterator for Geodesic {
    type Item = Leg;

    fn next(&mut self) -> Option<Leg> {
        match self.before_step() {
            Next::Given(leg) => leg,
            Next::Step => {
                let leg = self.step();
                Some(self.after_step(leg))
            }
        }
    }
}

impl Geodesic {
    /// The start of [`Iterator::next`]: whether the next leg is a step
    /// ([`Geodesic::step`], then [`Geodesic::after_step`]) or given
    /// without one.
    fn before_step(&mut self) -> Next {
        if self.done {
            return Next::Given(None);
        }
        let m = self.mass;
        let r = self.x.length();
        let outgoing = self.x.dot(self.v) >= 0.0;
        if r <= 2.0 * m || (r <= 3.0 * m && !outgoing) || self.chords >= MAX_CHORDS {
            self.done = true;
            return Next::Given(Some(Leg::Captured));
        }
        if r >= self.far && outgoing {
            // Past every object and moving out: it never turns back (no
            // turning point of r lies outside the photon sphere on the way out).
            self.done = true;
            self.escaped = true;
            self.cleared = false;
            let dt = self.outset().time_rate();
            let n = self.v.normalize();
            let ray = Ray {
                origin: Event::new(self.t, self.centre + self.x),
                direction: FourVector::new(self.time_sign * dt / self.v.length(), n),
            };
            return Next::Given(Some(Leg::Chord(ray, f64::INFINITY)));
        }
        self.chords += 1;
        Next::Step
    }

    /// The end of [`Iterator::next`] once its step gave `leg`.
    fn after_step(&mut self, leg: Leg) -> Leg {
        if leg == Leg::Captured {
            self.done = true;
        }
        leg
    }
}

mod integrator;
mod lanes;
mod stepping;

#[cfg(test)]
mod tests;
