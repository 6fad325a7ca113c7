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

/// A chord sized to the pixel strays by at most this fraction of its
/// start's height above the horizon.
const HEIGHT_FRACTION: f64 = 1.0 / 16.0;

/// No step of the integration is longer than this fraction of the radius
/// it starts at, however loose the chord tolerance: the accuracy of the
/// ray's direction, and so of where it goes, rests on it.
const LONGEST_STEP: f64 = 0.25;

/// Where the ray passes clear of every object, a step may be this
/// fraction of the radius it starts at, or less so that its path turns by
/// at most [`CLEAR_TURN`] radians: the chord can meet nothing, only the
/// integration's accuracy bounds it.
const CLEAR_STEP: f64 = 0.5;

/// The most a ray's path turns over one step clear of every object.
const CLEAR_TURN: f64 = 0.2;

/// A step clear of every object is taken where its estimated error is at
/// most this fraction of the chord tolerance in position and of the pixel's
/// angle in direction.
const CLEAR_ERROR: f64 = 1.0 / 16.0;

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

/// What stays the same along a geodesic's path: M, h^2 = |x cross v|^2
/// and sqrt(C), C = v^2 - 2 M h^2 / r^3 (the central acceleration's
/// angular momentum and energy).
#[derive(Clone, Copy)]
struct Invariants {
    m: f64,
    h2: f64,
    root_c: f64,
}

impl Invariants {
    fn of(m: f64, x: DVec3, v: DVec3) -> Invariants {
        let h2 = x.cross(v).length_squared();
        let r = x.length();
        let c = v.length_squared() - 2.0 * m * h2 / (r * r * r);
        Invariants {
            m,
            h2,
            root_c: c.max(0.0).sqrt(),
        }
    }

    /// d/d(lambda) of (x, v, t) (t's with `time_sign` applied by the
    /// caller): a = -3 M h^2 x / r^5, and from the null condition
    /// dt/dlambda = sqrt(v_r^2 / f^2 + v_t^2 / f) = sqrt(C) / f, since
    /// v_r^2 + f v_t^2 = v^2 - (2M / r) h^2 / r^2 = C.
    fn derivative(&self, x: DVec3, v: DVec3) -> (DVec3, DVec3, f64) {
        let r2 = x.length_squared();
        let r = r2.sqrt();
        let a = x * (-3.0 * self.m * self.h2 / (r2 * r2 * r));
        let dt = self.root_c * r / (r - 2.0 * self.m);
        (v, a, dt)
    }
}

/// The longest chord that strays by at most `tol` from a geodesic of
/// h = |x cross v| and C = v^2 - 2 M h^2 / r^3 (both conserved: the
/// central acceleration's angular momentum and energy) wherever its radius
/// is at least `r` (docs/physics.md, "Chords"). Its path curves by
/// kappa = 3 M h^2 / (r^4 v^2) = 3 M h^2 / (C r^4 + 2 M h^2 r), which
/// grows as r falls, and its dt/ds changes by at most
/// M cos(psi) (2 + 3 sin^2 psi) / (r^2 f^2) <= 2.485 M / (r^2 f^2) per unit
/// length; a chord of length L strays by L^2 / 8 times the larger of them.
fn longest_chord(m: f64, r: f64, h2: f64, c: f64, tol: f64) -> f64 {
    let f = 1.0 - 2.0 * m / r;
    if f <= 0.0 || r <= 0.0 {
        return 0.0;
    }
    let bending = bending(m, r, h2, c);
    let timing = 2.485 * m / (r * r * f * f);
    (8.0 * tol / bending.max(timing)).sqrt()
}
/// The curvature bound kappa = 3 M h^2 / (C r^4 + 2 M h^2 r) of the path
/// of a geodesic of h = |x cross v| and C = v^2 - 2 M h^2 / r^3 wherever
/// its radius is at least `r` ([`longest_chord`]).
fn bending(m: f64, r: f64, h2: f64, c: f64) -> f64 {
    3.0 * m * h2 / (c * r.powi(4) + 2.0 * m * h2 * r)
}

/// Whether the segment from `a` to `b` meets the box [`lo`, `hi`].
fn segment_meets_box(a: DVec3, b: DVec3, (lo, hi): (DVec3, DVec3)) -> bool {
    if lo.cmpgt(hi).any() {
        return false;
    }
    let d = b - a;
    let (mut enter, mut leave) = (0.0_f64, 1.0_f64);
    for i in 0..3 {
        if d[i] == 0.0 {
            if a[i] < lo[i] || a[i] > hi[i] {
                return false;
            }
            continue;
        }
        let inverse = 1.0 / d[i];
        let (near, far) = ((lo[i] - a[i]) * inverse, (hi[i] - a[i]) * inverse);
        enter = enter.max(near.min(far));
        leave = leave.min(near.max(far));
        if enter > leave {
            return false;
        }
    }
    true
}

/// The least radius an arc from `a` to `b` turning by at most CLEAR_TURN
/// can pass: the chord's, less the most the arc strays from it.
fn least_radius(a: DVec3, b: DVec3) -> f64 {
    distance_to_segment(a, b) - CLEAR_TURN * (b - a).length()
}

/// The distance from the origin to the segment from `a` to `b`.
fn distance_to_segment(a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let s = if len2 > 0.0 {
        (-a.dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + d * s).length()
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

    /// One classical Runge-Kutta step of `h` in lambda from (x, v).
    fn rk4(&self, h: f64) -> (DVec3, DVec3, f64) {
        let (x, v) = (self.x, self.v);
        let orbit = Invariants::of(self.mass, x, v);
        let (k1x, k1v, k1t) = orbit.derivative(x, v);
        let (k2x, k2v, k2t) = orbit.derivative(x + k1x * (h / 2.0), v + k1v * (h / 2.0));
        let (k3x, k3v, k3t) = orbit.derivative(x + k2x * (h / 2.0), v + k2v * (h / 2.0));
        let (k4x, k4v, k4t) = orbit.derivative(x + k3x * h, v + k3v * h);
        let dx = (k1x + (k2x + k3x) * 2.0 + k4x) * (h / 6.0);
        let dv = (k1v + (k2v + k3v) * 2.0 + k4v) * (h / 6.0);
        let dt = (k1t + 2.0 * (k2t + k3t) + k4t) * (h / 6.0);
        (x + dx, v + dv, dt)
    }

    /// One Dormand-Prince step of `h` in lambda from (x, v): the fifth
    /// order solution, and the difference from the embedded fourth order
    /// one in x and in v (the step's error estimate).
    fn dopri(&self, h: f64) -> ((DVec3, DVec3, f64), DVec3, DVec3) {
        const A: [[f64; 6]; 6] = [
            [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
            [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
            [
                19372.0 / 6561.0,
                -25360.0 / 2187.0,
                64448.0 / 6561.0,
                -212.0 / 729.0,
                0.0,
                0.0,
            ],
            [
                9017.0 / 3168.0,
                -355.0 / 33.0,
                46732.0 / 5247.0,
                49.0 / 176.0,
                -5103.0 / 18656.0,
                0.0,
            ],
            [
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
        ];
        const E: [f64; 7] = [
            35.0 / 384.0 - 5179.0 / 57600.0,
            0.0,
            500.0 / 1113.0 - 7571.0 / 16695.0,
            125.0 / 192.0 - 393.0 / 640.0,
            -2187.0 / 6784.0 + 92097.0 / 339200.0,
            11.0 / 84.0 - 187.0 / 2100.0,
            -1.0 / 40.0,
        ];
        let orbit = Invariants::of(self.mass, self.x, self.v);
        let mut kx = [DVec3::ZERO; 7];
        let mut kv = [DVec3::ZERO; 7];
        let mut kt = [0.0; 7];
        (kx[0], kv[0], kt[0]) = orbit.derivative(self.x, self.v);
        let mut end = (self.x, self.v, 0.0);
        for (i, row) in A.iter().enumerate() {
            let (mut x, mut v, mut t) = (self.x, self.v, 0.0);
            for j in 0..=i {
                x += kx[j] * (h * row[j]);
                v += kv[j] * (h * row[j]);
                t += kt[j] * (h * row[j]);
            }
            (kx[i + 1], kv[i + 1], kt[i + 1]) = orbit.derivative(x, v);
            end = (x, v, t);
        }
        let (mut ex, mut ev) = (DVec3::ZERO, DVec3::ZERO);
        for j in 0..7 {
            ex += kx[j] * (h * E[j]);
            ev += kv[j] * (h * E[j]);
        }
        (end, ex, ev)
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

    /// How far the next chord may stray from the geodesic.
    /// However coarse the pixel, never more than [`HEIGHT_FRACTION`] of the
    /// height above the horizon, so that the bounds are taken outside it.
    fn tolerance(&self) -> f64 {
        let height = self.x.length() - 2.0 * self.mass;
        let footprint = PIXEL_FRACTION * self.pixel_angle * self.arc;
        (CHORD_TOLERANCE * self.mass).max(footprint.min(HEIGHT_FRACTION * height))
    }

    /// The next chord: a step clear of all geometry where one longer than
    /// [`LONGEST_STEP`] of the radius can be taken ([`Geodesic::clear_step`]);
    /// otherwise one step, as long as the chord bound allows at the least
    /// radius the straight line along v would pass, halved until the chord
    /// is within the tolerance of the arc it cuts (measured at the least
    /// radius it passes, less the tolerance itself), and never longer than
    /// [`LONGEST_STEP`] of the radius.
    fn step(&mut self) -> Leg {
        let m = self.mass;
        let r = self.x.length();
        let speed = self.v.length();
        let h2 = self.x.cross(self.v).length_squared();
        let c = speed * speed - 2.0 * m * h2 / (r * r * r);
        let tol = self.tolerance();
        let allowed =
            |nearest: f64| longest_chord(m, nearest - tol, h2, c, tol).min(LONGEST_STEP * r);
        if let Some(leg) = self.clear_step(LONGEST_STEP * r, h2, c, tol) {
            return leg;
        }
        let ahead = self.v / speed;
        let mut len = allowed(r);
        for _ in 0..2 {
            len = allowed(distance_to_segment(self.x, self.x + ahead * len));
        }
        let mut h = 0.95 * len / speed;
        for _ in 0..40 {
            let (x, v, dt) = self.rk4(h);
            let len = (x - self.x).length();
            if len > 0.0 && len <= allowed(distance_to_segment(self.x, x)) && x.is_finite() {
                self.cleared = false;
                return self.advance(x, v, dt, len);
            }
            h /= 2.0;
        }
        Leg::Captured
    }

    /// A step longer than `len` along which nothing can be met: its arc
    /// keeps more than `tol` outside the box holding all geometry and turns
    /// by at most [`CLEAR_TURN`] ([`Geodesic::meets_geometry`]). It is one
    /// Dormand-Prince 5(4) step of at most [`CLEAR_STEP`] of the radius,
    /// taken when its error estimate is within [`CLEAR_ERROR`] of the chord
    /// tolerance in position and of the pixel's angle in direction, and
    /// shortened (by the estimate's fourth root, three tries) where it is
    /// not; the length that passed is tried first next time (and, where it
    /// was no longer than a chord, half as long again). `None` where no
    /// such step is longer than `len`, where the straight line ahead
    /// meets the box, and for a geodesic not sized to a pixel.
    fn clear_step(&mut self, len: f64, h2: f64, c: f64, tol: f64) -> Option<Leg> {
        let turning = self.pixel_angle * CLEAR_ERROR;
        let r = self.x.length();
        let speed = self.v.length();
        let mut clear = self.clear_fraction * r;
        for _ in 0..3 {
            let (lo, hi) = self.geometry;
            let margin = DVec3::splat(tol);
            let ahead = self.x + self.v * (clear / speed);
            if !(clear > len && turning > 0.0) {
                // No longer than a chord here: try longer again later.
                self.clear_fraction = (self.clear_fraction * 1.5).min(CLEAR_STEP);
                return None;
            }
            if segment_meets_box(self.x, ahead, (lo - margin, hi + margin)) {
                return None;
            }
            let ((x, v, dt), ex, ev) = self.dopri(clear / speed);
            let error = (ex.length() / (tol * CLEAR_ERROR)).max(ev.length() / (speed * turning));
            let scale = (0.9 / error.sqrt().sqrt()).clamp(0.2, 2.0);
            self.clear_fraction = (self.clear_fraction * scale).min(CLEAR_STEP);
            let turn = match self.meets_geometry(x, h2, c, tol) {
                Some(turn) if x.is_finite() => turn,
                _ => return None,
            };
            if error <= 1.0 && turn <= CLEAR_TURN && x != self.x {
                self.cleared = true;
                return Some(self.advance(x, v, dt, (x - self.x).length()));
            }
            clear *= scale.min(0.9 * CLEAR_TURN / turn);
        }
        None
    }

    /// How far the arc from here to `end` turns, if it keeps more than
    /// `tol` outside the box holding all geometry: it lies within the
    /// sagitta (1 - sqrt(1 - (kappa L / 2)^2)) / kappa of its chord of
    /// length L, kappa the bending at the least radius it can pass; `None`
    /// where it may come nearer (or the bound fails: kappa L >= 2, or the
    /// least radius inside the photon sphere).
    fn meets_geometry(&self, end: DVec3, h2: f64, c: f64, tol: f64) -> Option<f64> {
        let len = (end - self.x).length();
        let least = least_radius(self.x, end);
        let kappa = bending(self.mass, least, h2, c);
        let half = 0.5 * kappa * len;
        if !(least > 3.0 * self.mass && kappa >= 0.0 && half < 1.0) {
            return None;
        }
        let sagitta = 0.5 * len * half / (1.0 + (1.0 - half * half).sqrt());
        let margin = DVec3::splat(1.01 * sagitta + tol);
        let (lo, hi) = self.geometry;
        match segment_meets_box(self.x, end, (lo - margin, hi + margin)) {
            true => None,
            false => Some(2.0 * half),
        }
    }

    /// Moves on to (x, v), `dt` later in lambda's direction, giving the
    /// chord of length `len` from here.
    fn advance(&mut self, x: DVec3, v: DVec3, dt: f64, len: f64) -> Leg {
        let dt = dt * self.time_sign;
        let ray = Ray {
            origin: Event::new(self.t, self.centre + self.x),
            direction: FourVector::new(dt / len, (x - self.x) / len),
        };
        self.x = x;
        self.v = v;
        self.t += dt;
        self.arc += len;
        Leg::Chord(ray, len)
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

impl Iterator for Geodesic {
    type Item = Leg;

    fn next(&mut self) -> Option<Leg> {
        if self.done {
            return None;
        }
        let m = self.mass;
        let r = self.x.length();
        let outgoing = self.x.dot(self.v) >= 0.0;
        if r <= 2.0 * m || (r <= 3.0 * m && !outgoing) || self.chords >= MAX_CHORDS {
            self.done = true;
            return Some(Leg::Captured);
        }
        if r >= self.far && outgoing {
            // Past every object and moving out: it never turns back (no
            // turning point of r lies outside the photon sphere on the way out).
            self.done = true;
            self.escaped = true;
            self.cleared = false;
            let (_, _, dt) = Invariants::of(m, self.x, self.v).derivative(self.x, self.v);
            let n = self.v.normalize();
            let ray = Ray {
                origin: Event::new(self.t, self.centre + self.x),
                direction: FourVector::new(self.time_sign * dt / self.v.length(), n),
            };
            return Some(Leg::Chord(ray, f64::INFINITY));
        }
        self.chords += 1;
        let leg = self.step();
        if leg == Leg::Captured {
            self.done = true;
        }
        Some(leg)
    }
}

#[cfg(test)]
mod tests;
