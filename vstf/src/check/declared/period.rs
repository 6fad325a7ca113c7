//! Time-dilated materials: an object that blinks every P t.units of its own
//! proper time, moving uniformly. Measured from an animation of the object
//! alone: the period with which the camera sees it blink (on: its mean
//! colour past the midpoint between its base and blink colours, in the
//! channel where they differ most).
//! Expected from first principles: each switch happens at a proper time m P
//! on the object's clock (time dilation puts it at lab time t0 + gamma m P
//! for its reference point), and is seen one light time later (the changing
//! light delay): approaching, the camera sees the blinking faster; receding,
//! slower.

use crate::check::row::Reading;
use crate::fixture::checks::PeriodSpec;
use crate::fixture::{Fixture, Overrides};
use crate::observer::Observer;
use crate::oracle::{body_point, gamma, retarded};
use glam::DVec3;
use renderer::{Event, Model, ObjectKind, Shape, Traversal};

/// The camera times at which the plate is first seen switching on, from
/// the frames: midway between the last frame seen off and the first seen on.
fn measured_switches(frames: &[(f64, Option<bool>)]) -> Vec<f64> {
    frames
        .windows(2)
        .filter_map(|w| match (w[0].1, w[1].1) {
            (Some(false), Some(true)) => Some((w[0].0 + w[1].0) / 2.0),
            _ => None,
        })
        .collect()
}

/// The animation's camera times: `from` to `to` (inclusive) by `step`.
#[derive(Clone, Copy, Debug)]
struct Frames {
    from: f64,
    to: f64,
    step: f64,
}

/// The object through the animation: for each frame, the camera time and
/// whether it is seen on (None: not seen).
type Sightings = Vec<(f64, Option<bool>)>;

/// How a frame tells on from off: the mean colour of the object's pixels
/// in `channel` beyond `threshold`, above it if the blink colour is the
/// brighter there.
#[derive(Clone, Copy, Debug)]
struct OnOff {
    channel: usize,
    threshold: f64,
    brighter: bool,
}

impl OnOff {
    /// The midpoint between the base and blink colours in the channel where
    /// they differ most (the first of equals).
    fn between(base: DVec3, blink: DVec3) -> OnOff {
        let d = (blink - base).abs();
        let channel = if d.x >= d.y.max(d.z) {
            0
        } else if d.y >= d.z {
            1
        } else {
            2
        };
        OnOff {
            channel,
            threshold: (base[channel] + blink[channel]) / 2.0,
            brighter: blink[channel] > base[channel],
        }
    }

    fn is_on(&self, mean: DVec3) -> bool {
        if self.brighter {
            mean[self.channel] > self.threshold
        } else {
            mean[self.channel] < self.threshold
        }
    }
}

/// Renders the animation of `f` (the measured object alone) under `model`
/// and reports for each frame whether the object is seen on; None when it
/// is not seen.
fn animate(f: &Fixture, model: Model, frames: &Frames, on: OnOff) -> Result<Sightings, String> {
    let Frames { from, to, step } = *frames;
    let view = crate::run::view(
        f,
        &Overrides {
            model: Some(model),
            width: Some(96),
            height: Some(72),
            spp: Some(1),
            ..Default::default()
        },
    )?;
    let db = crate::run::database_shared(f, model.lorentz, Traversal::Bvh)?;
    let times: Vec<f64> = (0..=((to - from) / step).round() as usize)
        .map(|i| from + step * i as f64)
        .collect();
    let mut seen = Sightings::new();
    for &t in &times {
        let img = crate::run::render_with(
            &db,
            f,
            &crate::fixture::View {
                camera_t: t,
                ..view
            },
        )?;
        let (mut n, mut sum) = (0.0, DVec3::ZERO);
        for p in &img.pixels {
            if (*p - f.scene.background).length() > 0.05 {
                n += 1.0;
                sum += *p;
            }
        }
        seen.push((t, (n > 0.0).then(|| on.is_on(sum / n))));
    }
    Ok(seen)
}

/// A blinking object's worldline, clock and colours, and the points of
/// it whose seen switches spread the switch seen in its mean colour (its
/// mesh's vertices, or a sphere's six poles), read from the fixture.
struct Blinker {
    start: Event,
    velocity: DVec3,
    /// The blink period in the object's proper time, t.units.
    period: f64,
    /// Whether its clock is dilated (a V_obj under the Lorentz transform);
    /// otherwise it reads lab time.
    dilated: bool,
    on: OnOff,
    extremes: Vec<DVec3>,
}

impl Blinker {
    fn of(f: &Fixture, name: &str, model: Model) -> Result<Blinker, String> {
        let obj = f.object(name)?;
        let blink = obj
            .material
            .blink
            .ok_or_else(|| format!("{name} does not blink"))?;
        let (start, velocity) = crate::observer::uniform(&obj.motion)
            .ok_or_else(|| format!("{name} must move uniformly"))?;
        let extremes = match &obj.shape {
            Shape::Mesh(m) => m.vertices.clone(),
            Shape::Sphere { radius } => [DVec3::X, DVec3::Y, DVec3::Z]
                .iter()
                .flat_map(|a| [*a * *radius, -*a * *radius])
                .collect(),
        };
        Ok(Blinker {
            start,
            velocity,
            period: blink.period,
            dilated: model.lorentz && obj.kind == ObjectKind::VObj,
            on: OnOff::between(obj.material.color, blink.color),
            extremes,
        })
    }
}

/// The blink period the camera at `cam` sees between the switches nearest
/// the first and last of `switches`, and its uncertainty.
fn expected_period(
    b: &Blinker,
    cam: DVec3,
    switches: &[f64],
    step: f64,
) -> Result<(f64, f64), String> {
    let (start, v, period, dilated) = (b.start, b.velocity, b.period, b.dilated);
    let g = if dilated { gamma(v.length()) } else { 1.0 };
    // Switch m happens at proper time m P. With the object's clock dilated,
    // the point at rest offset r' (lab offset r, contracted) reads it at lab
    // time t0 + gamma (m P + gamma v.r) (t = gamma (t' + v.r')); without, at
    // lab time t0 + m P everywhere. It is seen a light time later.
    let seen_at = |m: f64, r: DVec3| {
        let p = body_point(start.t, start.x, v, r, dilated);
        let t = if dilated {
            let offset = crate::oracle::contract(r, v);
            start.t + g * (m * period + g * v.dot(offset))
        } else {
            start.t + m * period
        };
        t + (p.at(t) - cam).length()
    };
    // The switch numbers m nearest to the first and last measured switches.
    let nearest = |t: f64| -> Option<f64> {
        let mut m = 0.0;
        for _ in 0..MAX_SWITCHES {
            if seen_at(m + 1.0, DVec3::ZERO) > t {
                let after = (seen_at(m + 1.0, DVec3::ZERO) - t).abs();
                return Some(if after < (seen_at(m, DVec3::ZERO) - t).abs() {
                    m + 1.0
                } else {
                    m
                });
            }
            m += 1.0;
        }
        None
    };
    let n = (switches.len() - 1) as f64;
    let first = nearest(switches[0]);
    let last = nearest(switches[switches.len() - 1]);
    let (m0, m1) = first
        .zip(last)
        .filter(|(m0, m1)| m1 > m0)
        .ok_or_else(|| {
            format!("the switches seen do not match distinct switches of the object's clock (more than {MAX_SWITCHES} periods, or before its start)")
        })?;
    let expected = (seen_at(m1, DVec3::ZERO) - seen_at(m0, DVec3::ZERO)) / (m1 - m0);
    // Uncertainty: each switch is known to within half a frame step; the
    // object's extent (its extreme points switch at other seen times) may
    // shift the switch seen in the average colour by up to the change of
    // that spread between the first and last switches.
    let spread = |m: f64| {
        b.extremes
            .iter()
            .map(|&r| seen_at(m, r) - seen_at(m, DVec3::ZERO))
            .fold(0.0f64, |a, b| a.max(b.abs()))
    };
    let tolerance = (step + (spread(m1) - spread(m0)).abs() + spread(m0).max(spread(m1))) / n;
    Ok((expected, tolerance))
}

/// The most blink periods counted from the object's start to a seen switch.
const MAX_SWITCHES: usize = 10_000_000;

/// The blink period the object of `p` is seen with, measured from an
/// animation of `measuring`'s camera against the dilated, light-delayed
/// period expected from `described`; and where its reference point is seen
/// at the view's camera time, to mark. The animation is the same at every
/// effort: its precision is set by the frame step.
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    p: &PeriodSpec,
) -> Result<(Reading, f64, Option<DVec3>), String> {
    let frames = Frames {
        from: p.from,
        to: p.to,
        step: p.step,
    };
    let b = Blinker::of(described.fixture, &p.object, described.model)?;
    let alone = measuring
        .fixture
        .only(&[p.object.as_str()])
        .map_err(|e| e.to_string())?;
    let switches = measured_switches(&animate(&alone, measuring.model, &frames, b.on)?);
    if switches.len() < 3 {
        return Err(format!(
            "{} was seen switching on only {} times between camera times {} and {}",
            p.object,
            switches.len(),
            p.from,
            p.to
        ));
    }
    let n = (switches.len() - 1) as f64;
    let measured = (switches[switches.len() - 1] - switches[0]) / n;
    let cam = described.camera_x();
    let (expected, tolerance) = expected_period(&b, cam, &switches, p.step)?;
    let centre = body_point(b.start.t, b.start.x, b.velocity, DVec3::ZERO, b.dilated);
    let mark = retarded(&centre, described.camera_t, cam).map(|r| r.direction);
    Ok((
        Reading {
            value: measured,
            tolerance,
        },
        expected,
        mark,
    ))
}
