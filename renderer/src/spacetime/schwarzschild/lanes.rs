//! Four geodesics stepped side by side: at each round, the trials
//! (Dormand-Prince or Runge-Kutta) that two or more of them need are
//! computed together in `f64x4`, while every decision stays each
//! geodesic's own, so that each gives the legs it gives alone, to the bit.
//! A trial's square roots and divisions are a large part of a step's
//! cost; four lanes of them take about half as long as four single trials
//! (docs/performance.md, "Stop 55").

use super::integrator::Outsets4;
use super::stepping::{Ask, Step};
use super::{Geodesic, Leg, Next};

/// Fewer lanes than this needing the same trial take it one by one.
const BATCHED_FROM: usize = 2;

impl Geodesic {
    /// [`Iterator::next`] of each geodesic present in `lanes`, the same
    /// legs to the bit (`None` for an absent lane).
    pub fn next_each(lanes: &mut [Option<Geodesic>; 4]) -> [Option<Leg>; 4] {
        let mut legs = [None; 4];
        let mut steps: [Option<Step>; 4] = [None, None, None, None];
        for ((lane, step), leg) in lanes.iter_mut().zip(&mut steps).zip(&mut legs) {
            if let Some(g) = lane {
                match g.before_step() {
                    Next::Step => *step = Some(g.begin_step()),
                    Next::Given(given) => *leg = given,
                }
            }
        }
        while steps.iter().any(Option::is_some) {
            let (mut asks, mut captured) = ([None; 4], [None; 4]);
            for j in 0..4 {
                if let (Some(g), Some(step)) = (&mut lanes[j], &mut steps[j]) {
                    match g.ask(step) {
                        Ask::Captured => captured[j] = Some(Leg::Captured),
                        ask => asks[j] = Some(ask),
                    }
                }
            }
            let done = round(lanes, &mut steps, &asks);
            for j in 0..4 {
                if let (Some(leg), Some(g)) = (captured[j].or(done[j]), &mut lanes[j]) {
                    legs[j] = Some(g.after_step(leg));
                    steps[j] = None;
                }
            }
        }
        legs
    }
}

/// One round of trials: each lane asking for one gets it, batched where
/// [`BATCHED_FROM`] or more ask for the same kind; the legs of the lanes
/// whose step ended.
fn round(
    lanes: &mut [Option<Geodesic>; 4],
    steps: &mut [Option<Step>; 4],
    asks: &[Option<Ask>; 4],
) -> [Option<Leg>; 4] {
    let dopri = asks.map(|a| match a {
        Some(Ask::Dopri(h)) => Some(h),
        _ => None,
    });
    let rk4 = asks.map(|a| match a {
        Some(Ask::Rk4(h)) => Some(h),
        _ => None,
    });
    let dopri_found = trials(
        steps,
        dopri,
        |o, h| o.dopri(h),
        |s, h| s.outset.dopri_trial(h),
    );
    let rk4_found = trials(steps, rk4, |o, h| o.rk4(h), |s, h| s.outset.rk4_trial(h));
    let mut done = [None; 4];
    for j in 0..4 {
        let (Some(g), Some(step)) = (&mut lanes[j], &mut steps[j]) else {
            continue;
        };
        done[j] = match (dopri_found[j], rk4_found[j]) {
            (Some(found), _) => g.after_dopri(step, found),
            (_, Some(found)) => g.after_rk4(step, found),
            _ => None,
        };
    }
    done
}

/// The trial of each lane with an `h` in `asked`: four side by side
/// (`batched`, the lanes not asking repeating one that is) where enough
/// ask, else one by one (`single`).
fn trials<R: Copy>(
    steps: &[Option<Step>; 4],
    asked: [Option<f64>; 4],
    batched: impl Fn(&Outsets4, [f64; 4]) -> [R; 4],
    single: impl Fn(&Step, f64) -> R,
) -> [Option<R>; 4] {
    let asking = asked.iter().filter(|h| h.is_some()).count();
    let mut found = [None; 4];
    if asking >= BATCHED_FROM {
        let first = asked.iter().position(Option::is_some).unwrap_or(0);
        let pick = |j: usize| if asked[j].is_some() { j } else { first };
        let outset = |j: usize| &steps[pick(j)].as_ref().expect("a step asks").outset;
        let h = std::array::from_fn(|j| asked[pick(j)].unwrap_or(0.0));
        let lanes = Outsets4::of([outset(0), outset(1), outset(2), outset(3)]);
        let all = batched(&lanes, h);
        for j in 0..4 {
            if asked[j].is_some() {
                found[j] = Some(all[j]);
            }
        }
    } else {
        for j in 0..4 {
            if let (Some(h), Some(step)) = (asked[j], &steps[j]) {
                found[j] = Some(single(step, h));
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::super::{Event, LightSpeed, Schwarzschild};
    use super::*;
    use glam::DVec3;

    /// Rays from one camera event through a mass's field, of every fate:
    /// captured, passing near the photon sphere, chords through a box of
    /// geometry, steps clear of it, escaping.
    fn geodesics(turn: f64) -> Vec<Geodesic> {
        let hole = Schwarzschild {
            mass: 0.5,
            centre: DVec3::new(1.0, -2.0, 3.0),
        };
        let eye = Event::new(7.0, hole.centre + DVec3::new(0.3, 2.0, 30.0));
        let (lo, hi) = (
            hole.centre - DVec3::splat(8.0),
            hole.centre + DVec3::new(8.0, 8.0, -4.0),
        );
        (0..11)
            .map(|k| {
                let b = f64::from(k) * 0.45 + turn;
                let towards = DVec3::new(0.02 * b, -0.07 + 0.031 * b, -1.0).normalize();
                Geodesic::backwards(&hole, eye, towards, LightSpeed::Finite, 40.0)
                    .sized_to_pixel(1e-3)
                    .with_geometry_in(lo, hi)
            })
            .collect()
    }

    /// Each geodesic's legs, as bits, with whether each chord passed clear.
    fn legs_alone(mut g: Geodesic) -> Vec<(Vec<u64>, bool)> {
        std::iter::from_fn(|| g.next().map(|leg| (bits(leg), g.passed_clear()))).collect()
    }

    fn bits(leg: Leg) -> Vec<u64> {
        match leg {
            Leg::Chord(ray, len) => {
                let (o, d) = (ray.origin, ray.direction);
                [o.t, o.x.x, o.x.y, o.x.z, d.t, d.x.x, d.x.y, d.x.z, len]
                    .map(f64::to_bits)
                    .to_vec()
            }
            Leg::Captured => Vec::new(),
        }
    }

    /// The legs of `each` stepped four at a time, a lane refilled with the
    /// next geodesic as soon as its own has given its last leg.
    fn legs_side_by_side(each: Vec<Geodesic>) -> Vec<Vec<(Vec<u64>, bool)>> {
        let mut legs = vec![Vec::new(); each.len()];
        let mut queue = each.into_iter().enumerate();
        let mut lanes: [Option<Geodesic>; 4] = [None, None, None, None];
        let mut whose = [0; 4];
        loop {
            for j in 0..4 {
                if lanes[j].is_none() {
                    if let Some((k, g)) = queue.next() {
                        (lanes[j], whose[j]) = (Some(g), k);
                    }
                }
            }
            if lanes.iter().all(Option::is_none) {
                return legs;
            }
            for (j, leg) in Geodesic::next_each(&mut lanes).into_iter().enumerate() {
                match (leg, &lanes[j]) {
                    (Some(leg), Some(g)) => legs[whose[j]].push((bits(leg), g.passed_clear())),
                    _ => lanes[j] = None,
                }
            }
        }
    }

    /// Every geodesic gives the same legs to the bit stepped with three
    /// others as alone, lanes ending and refilled at different times; the
    /// rays are of every fate, so both trials are batched and taken one by
    /// one. Negative control: rays turned by a part in 1e12 give other legs
    /// (the comparison sees a difference in the last bits).
    #[test]
    fn geodesics_side_by_side_give_the_legs_they_give_alone() {
        let alone: Vec<_> = geodesics(0.0).into_iter().map(legs_alone).collect();
        assert_eq!(legs_side_by_side(geodesics(0.0)), alone);
        let captured = alone
            .iter()
            .filter(|l| l.last().is_some_and(|l| l.0.is_empty()));
        let escaped = alone
            .iter()
            .filter(|l| l.last().is_some_and(|l| l.0.len() == 9));
        assert!(captured.count() > 0 && escaped.count() > 0, "every fate");
        let clear = alone.iter().flatten().filter(|l| l.1).count();
        assert!(
            clear > 0 && clear < alone.iter().flatten().count(),
            "both steps"
        );
        assert_ne!(legs_side_by_side(geodesics(1e-12)), alone);
    }
}
