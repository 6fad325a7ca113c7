//! Time-dilated materials: plates that blink every P = 2 t.units of their own
//! proper time, one approaching the camera at 0.5c and one receding. Measured
//! from an animation: the period with which the camera sees them blink.
//! Expected from first principles: each switch happens at a proper time m P
//! on the plate's clock (time dilation puts it at lab time t0 + gamma m P for
//! the plate's centre), and is seen one light time later (the changing light
//! delay): approaching, the camera sees the blinking faster; receding,
//! slower.

use super::{fixture_model, Effort, Findings, Quantity, Reading, Setup, Unit};
use crate::fixture::{Fixture, Overrides};
use crate::oracle::{body_point, gamma, retarded};
use glam::DVec3;
use renderer::{Event, Model, Motion, Traversal};

const NAME: &str = "blink";
struct Plate {
    name: &'static str,
    /// Which half of the image the plate is seen in.
    left: bool,
}

const PLATES: [Plate; 2] = [
    Plate {
        name: "approaching",
        left: true,
    },
    Plate {
        name: "receding",
        left: false,
    },
];

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

/// One plate through the animation: for each frame, the camera time and
/// whether the plate is seen on (None: not seen).
type Sightings = Vec<(f64, Option<bool>)>;

/// Renders the animation and reports, for each plate (in [`PLATES`] order)
/// and each frame, whether the plate is seen on (closer to its blink
/// colour, white) or off; None when not seen.
fn animate(f: &Fixture, model: Model, frames: &Frames) -> Result<Vec<Sightings>, String> {
    let Frames { from, to, step } = *frames;
    let view = crate::run::view(
        f,
        &Overrides {
            width: Some(96),
            height: Some(72),
            spp: Some(1),
            ..Default::default()
        },
    )?;
    let db = crate::run::database(f, model.lorentz, Traversal::Bvh)?;
    let times: Vec<f64> = (0..=((to - from) / step).round() as usize)
        .map(|i| from + step * i as f64)
        .collect();
    let mut seen: Vec<Sightings> = vec![Vec::new(), Vec::new()];
    for &t in &times {
        let img = crate::run::render_with(
            &db,
            f,
            &crate::fixture::View {
                camera_t: t,
                ..view
            },
        );
        for (k, plate) in PLATES.iter().enumerate() {
            let (mut n, mut sum) = (0.0, DVec3::ZERO);
            for (i, p) in img.pixels.iter().enumerate() {
                let x = (i as u32) % img.width;
                if (x < img.width / 2) == plate.left && p.length() > 0.05 {
                    n += 1.0;
                    sum += *p;
                }
            }
            let state = (n > 0.0).then(|| (sum / n).x > 0.55);
            seen[k].push((t, state));
        }
    }
    Ok(seen)
}

/// A blinking plate's worldline and clock, read from the fixture.
struct Blinker {
    start: Event,
    velocity: DVec3,
    /// The blink period in the plate's proper time, t.units.
    period: f64,
}

impl Blinker {
    fn of(f: &Fixture, plate: &Plate) -> Result<Blinker, String> {
        let obj = f
            .scene
            .objects
            .iter()
            .find(|o| o.name == plate.name)
            .ok_or("no plate")?;
        match (&obj.motion, obj.material.blink) {
            (
                Motion::Velocity {
                    start, velocity, ..
                },
                Some(b),
            ) => Ok(Blinker {
                start: *start,
                velocity: *velocity,
                period: b.period,
            }),
            _ => Err(format!(
                "{NAME}: {} must move by velocity and blink",
                plate.name
            )),
        }
    }
}

/// The blink period the camera at `cam` sees between the switches nearest
/// the first and last of `switches`, and its uncertainty.
fn expected_period(
    b: &Blinker,
    model: Model,
    cam: DVec3,
    switches: &[f64],
    step: f64,
) -> (f64, f64) {
    let (start, v, period) = (b.start, b.velocity, b.period);
    let g = if model.lorentz {
        gamma(v.length())
    } else {
        1.0
    };
    // Switch m happens at proper time m P; the point at offset r reads it
    // at lab time t0 + gamma (m P + gamma v.r') and is seen a light time later.
    let seen_at = |m: f64, r: DVec3| {
        let p = body_point(start.t, start.x, v, r, model.lorentz);
        let offset = if model.lorentz {
            crate::oracle::contract(r, v)
        } else {
            r
        };
        let t = start.t + g * (m * period + g * v.dot(offset));
        t + (p.at(t) - cam).length()
    };
    // The switch numbers m nearest to the first and last measured switches.
    let nearest = |t: f64| {
        let mut m = 0.0;
        while seen_at(m + 1.0, DVec3::ZERO) <= t {
            m += 1.0;
        }
        if (seen_at(m + 1.0, DVec3::ZERO) - t).abs() < (seen_at(m, DVec3::ZERO) - t).abs() {
            m + 1.0
        } else {
            m
        }
    };
    let n = (switches.len() - 1) as f64;
    let (m0, m1) = (nearest(switches[0]), nearest(switches[switches.len() - 1]));
    let expected = (seen_at(m1, DVec3::ZERO) - seen_at(m0, DVec3::ZERO)) / (m1 - m0);
    // Uncertainty: each switch is known to within half a frame step; the
    // plate's extent (its corners switch at other seen times) may shift
    // the switch seen in the average colour by up to the change of that
    // spread between the first and last switches.
    let corners = [
        DVec3::new(-0.5, -0.5, 0.0),
        DVec3::new(0.5, 0.5, 0.0),
        DVec3::new(-0.5, 0.5, 0.0),
        DVec3::new(0.5, -0.5, 0.0),
    ];
    let spread = |m: f64| {
        corners
            .iter()
            .map(|&r| seen_at(m, r) - seen_at(m, DVec3::ZERO))
            .fold(0.0f64, |a, b| a.max(b.abs()))
    };
    let tolerance = (step + (spread(m1) - spread(m0)).abs() + spread(m0).max(spread(m1))) / n;
    (expected, tolerance)
}

/// The blink period each plate is seen with, measured from the animation
/// against the dilated, light-delayed period. The animation is the same at
/// every effort: its precision is set by the frame step.
pub fn run(
    f: &Fixture,
    (from, to, step): (f64, f64, f64),
    _effort: &Effort,
) -> Result<Findings, String> {
    let frames = Frames { from, to, step };
    let model = fixture_model(f);
    let cam = f.spec.camera.position;
    let seen = animate(f, model, &frames)?;
    let mut quantities = Vec::new();
    let mut marks = Vec::new();
    for (k, plate) in PLATES.iter().enumerate() {
        let switches = measured_switches(&seen[k]);
        if switches.len() < 3 {
            return Err(format!(
                "{NAME}: the {} plate was seen switching on only {} times",
                plate.name,
                switches.len()
            ));
        }
        let n = (switches.len() - 1) as f64;
        let measured = (switches[switches.len() - 1] - switches[0]) / n;
        let b = Blinker::of(f, plate)?;
        let (expected, tolerance) = expected_period(&b, model, cam, &switches, step);
        quantities.push(Quantity {
            name: format!("{} plate: blink period seen by the camera", plate.name),
            measured: Reading {
                value: measured,
                tolerance,
            },
            expected,
            paper: None,
            unit: Unit::TUnits,
        });
        if let Some(r) = retarded(
            &body_point(b.start.t, b.start.x, b.velocity, DVec3::ZERO, model.lorentz),
            f.spec.camera.t,
            cam,
        ) {
            marks.push(r.direction);
        }
    }
    let setup = Setup {
        fixture: f,
        model,
        camera_t: f.spec.camera.t,
    };
    Ok(Findings {
        views: vec![setup.full_view("view", &marks)?],
        quantities,
    })
}
