use super::*;
use crate::math;

const M: f64 = 1.0;

fn hole() -> Schwarzschild {
    Schwarzschild {
        mass: M,
        centre: DVec3::new(3.0, -2.0, 5.0),
    }
}

/// The chords of the ray leaving `from` (relative to the centre) along
/// `towards`, and whether it was captured.
fn trace(from: DVec3, towards: DVec3, reach: f64) -> (Vec<(Ray, f64)>, bool) {
    let s = hole();
    let origin = Event::new(10.0, s.centre + from);
    let mut chords = Vec::new();
    let mut captured = false;
    for leg in Geodesic::backwards(&s, origin, towards, LightSpeed::Finite, reach) {
        match leg {
            Leg::Chord(ray, len) => chords.push((ray, len)),
            Leg::Captured => captured = true,
        }
    }
    (chords, captured)
}

/// A ray from far away along -x with impact parameter b (at rest far
/// away, the local frame is the coordinates').
fn passing(b: f64, r0: f64) -> (Vec<(Ray, f64)>, bool) {
    trace(DVec3::new(r0, b, 0.0), DVec3::NEG_X, r0)
}

#[test]
fn a_far_ray_is_deflected_by_the_weak_field_series() {
    // alpha = 4 (M/b) + 15 pi/4 (M/b)^2 + 128/3 (M/b)^3 + 3465 pi/64 (M/b)^4 + ...
    let b = 100.0;
    let (chords, captured) = passing(b, 1e6);
    assert!(!captured);
    let last = chords.last().unwrap().0.direction.x;
    // Bent towards the mass: the final direction has turned to -y.
    let alpha = math::atan2(-last.y, -last.x);
    let q = M / b;
    let pi = std::f64::consts::PI;
    let series = 4.0 * q
        + 15.0 * pi / 4.0 * q * q
        + 128.0 / 3.0 * q * q * q
        + 3465.0 * pi / 64.0 * q * q * q * q;
    // Next term ~ 3840/5 q^5 ~ 1e-7; finite distance ~ 2 M b / r0^2.
    assert!((alpha - series).abs() < 2e-7, "{alpha} vs {series}");
    assert!(chords.len() < 2_000, "{} chords", chords.len());
}

#[test]
fn rays_inside_the_critical_impact_parameter_fall_in() {
    let bc = 3.0 * 3f64.sqrt() * M;
    assert!(passing(bc * 0.995, 1e4).1, "captured just inside");
    assert!(!passing(bc * 1.005, 1e4).1, "escapes just outside");
    // Straight at the hole, and straight away from it.
    assert!(trace(DVec3::new(50.0, 0.0, 0.0), DVec3::NEG_X, 100.0).1);
    let (out, captured) = trace(DVec3::new(50.0, 0.0, 0.0), DVec3::X, 100.0);
    assert!(!captured && out.iter().all(|(r, _)| r.direction.x.y == 0.0));
}

#[test]
fn chords_are_continuous_in_space_and_coordinate_time() {
    let (chords, _) = passing(8.0, 200.0);
    for w in chords.windows(2) {
        let (a, len) = w[0];
        let end = a.at(len);
        let next = w[1].0.origin;
        assert!((end.x - next.x).length() < 1e-9 && (end.t - next.t).abs() < 1e-9);
    }
    // Far out, chords are straight light-cone rays: dt/ds -> -1.
    let last = chords.last().unwrap().0;
    assert!(
        (last.direction.t + 1.0).abs() < 0.02,
        "{}",
        last.direction.t
    );
}

#[test]
fn radial_coordinate_time_is_the_closed_form() {
    // Outward radially from r1 to r2: t = r2 - r1 + 2M ln((r2 - 2M)/(r1 - 2M)).
    let (r1, r2) = (4.0, 400.0);
    let (chords, captured) = trace(DVec3::new(0.0, 0.0, r1), DVec3::Z, r2);
    assert!(!captured);
    let (last, _) = chords.last().unwrap();
    let r_end = (last.origin.x - hole().centre).length();
    let elapsed = 10.0 - last.origin.t;
    let expected = r_end - r1 + 2.0 * M * math::ln((r_end - 2.0 * M) / (r1 - 2.0 * M));
    assert!(r_end >= r2);
    assert!(
        (elapsed - expected).abs() < 1e-6 * expected,
        "{elapsed} vs {expected}"
    );
}

/// The farthest any point of the geodesic (integrated with steps a
/// hundred times finer than each chord) lies from the chord cutting its
/// arc, in space and in coordinate time, for the ray passing at `b` from
/// `r0` with chords sized to a pixel of `pixel_angle`; and how many chords.
fn worst_stray(b: f64, r0: f64, pixel_angle: f64) -> (f64, f64, usize) {
    let everywhere = (DVec3::NEG_INFINITY, DVec3::INFINITY);
    worst_stray_in(b, r0, pixel_angle, everywhere, everywhere)
}

/// [`worst_stray`] for a geodesic told that all geometry lies in the box
/// `told`, among the points of the geodesic inside the box `seen` (both
/// relative to the centre).
fn worst_stray_in(
    b: f64,
    r0: f64,
    pixel_angle: f64,
    told: (DVec3, DVec3),
    seen: (DVec3, DVec3),
) -> (f64, f64, usize) {
    let s = hole();
    let origin = Event::new(10.0, s.centre + DVec3::new(r0, b, 0.0));
    let start = || {
        Geodesic::backwards(&s, origin, DVec3::NEG_X, LightSpeed::Finite, r0)
            .sized_to_pixel(pixel_angle)
    };
    let chords: Vec<(Ray, f64)> = start()
        .with_geometry_in(s.centre + told.0, s.centre + told.1)
        .map_while(|leg| match leg {
            Leg::Chord(ray, len) if len.is_finite() => Some((ray, len)),
            _ => None,
        })
        .collect();
    let mut fine = start();
    let (mut space, mut time): (f64, f64) = (0.0, 0.0);
    for (ray, len) in &chords {
        let h = len / fine.v.length() / 100.0;
        let d = ray.direction.x;
        while (fine.centre + fine.x - ray.origin.x).dot(d) < *len - 1e-12 {
            let p = fine.centre + fine.x - ray.origin.x;
            let along = p.dot(d).clamp(0.0, *len);
            if fine.x.cmpge(seen.0).all() && fine.x.cmple(seen.1).all() {
                space = space.max((p - d * along).length());
                let t = ray.origin.t + ray.direction.t * along;
                time = time.max((fine.t - t).abs());
            }
            let (x, v, dt) = fine.outset().rk4_trial(h);
            (fine.x, fine.v, fine.t) = (x, v, fine.t - dt);
        }
    }
    (space, time, chords.len())
}

#[test]
fn no_point_of_a_chord_strays_beyond_the_tolerance() {
    for b in [6.0, 20.0] {
        let (space, time, _) = worst_stray(b, 60.0, 0.0);
        let tol = CHORD_TOLERANCE * M;
        assert!(space <= tol && time <= tol, "b {b}: {space}, {time}");
        // The bound is not vacuous: the worst chord comes within a factor
        // of a few of it.
        assert!(space.max(time) > 0.1 * tol, "b {b}: {space}, {time}");
    }
}

/// Chords sized to a pixel of 1e-3 rad seen from 60 M: beyond the first
/// few M of the way each may stray by an eighth of the footprint there, and
/// no farther; fewer of them cut the same geodesic.
#[test]
fn chords_sized_to_a_pixel_stray_by_at_most_its_fraction_of_the_footprint() {
    let angle = 1e-3;
    let (space, time, n) = worst_stray(6.0, 60.0, angle);
    let (_, _, n_fine) = worst_stray(6.0, 60.0, 0.0);
    // The footprint at the far end of the stretch followed (about 120 M).
    let bound = PIXEL_FRACTION * angle * 130.0;
    assert!(
        space <= bound && time <= bound,
        "{space}, {time} vs {bound}"
    );
    assert!(
        space.max(time) > CHORD_TOLERANCE * M,
        "looser than the floor"
    );
    assert!(2 * n < n_fine, "{n} chords against {n_fine}");
}

/// With chords sized to a pixel of 1e-4 rad the ray's direction still
/// meets the one integrated with the finest chords to a twentieth of the
/// pixel: the steps' length is capped, so the integration stays accurate.
#[test]
fn chords_sized_to_a_pixel_keep_the_deflection() {
    let s = hole();
    let origin = Event::new(10.0, s.centre + DVec3::new(1e4, 100.0, 0.0));
    let last = |angle: f64| {
        let legs = Geodesic::backwards(&s, origin, DVec3::NEG_X, LightSpeed::Finite, 1e4)
            .sized_to_pixel(angle);
        let rays: Vec<DVec3> = legs
            .filter_map(|leg| match leg {
                Leg::Chord(ray, _) => Some(ray.direction.x),
                Leg::Captured => None,
            })
            .collect();
        (
            math::atan2(-rays[rays.len() - 1].y, -rays[rays.len() - 1].x),
            rays.len(),
        )
    };
    let ((coarse, n), (fine, n_fine)) = (last(1e-4), last(0.0));
    assert!((coarse - fine).abs() < 1e-4 / 20.0, "{coarse} vs {fine}");
    assert!(fine > 0.04, "bent: {fine}");
    // Fewer, longer chords (here most are as long as the step cap allows).
    assert!(4 * n < 3 * n_fine, "{n} chords against {n_fine}");
}

#[test]
fn a_zero_mass_is_flat() {
    assert_eq!(Spacetime::of_mass(0.0, DVec3::ONE), Spacetime::Flat);
    assert!(matches!(
        Spacetime::of_mass(1.0, DVec3::ONE),
        Spacetime::Schwarzschild(_)
    ));
}

/// Static clocks at r = 4M run at sqrt(1/2) of coordinate time and at
/// r = 100M at sqrt(0.98): light between them is shifted by the ratio,
/// either way; an emitter on the horizon sends nothing.
#[test]
fn static_observers_see_the_ratio_of_their_clock_rates() {
    let s = hole();
    let at = |r: f64| s.centre + DVec3::new(0.6, 0.0, 0.8) * r;
    let up = s.static_shift(at(4.0), at(100.0));
    assert!((up - (0.5f64 / 0.98).sqrt()).abs() < 1e-15, "{up}");
    assert!((s.static_shift(at(100.0), at(4.0)) * up - 1.0).abs() < 1e-15);
    assert_eq!(s.static_shift(at(2.0), at(100.0)), 0.0);
    assert!((s.lapse_squared(at(4.0)) - 0.5).abs() < 1e-15);
}

/// Light moves at 1 in every static frame: a radial null ray has
/// dr/dt = f and a transverse one r dphi/dt = sqrt(f), both unit speed
/// once taken into the static observer's frame, and a light direction
/// keeps its transverse part and loses none of its length.
#[test]
fn light_moves_at_one_in_the_static_frame() {
    let s = hole();
    let n = DVec3::new(0.0, 0.6, 0.8);
    let x = s.centre + n * 3.0;
    let f = 1.0 - 2.0 / 3.0;
    let t = DVec3::X;
    let (radial, _) = s.static_frame(x, n * f, n);
    let (across, _) = s.static_frame(x, t * f.sqrt(), t);
    assert!((radial.length() - 1.0).abs() < 1e-15, "{radial}");
    assert!((across.length() - 1.0).abs() < 1e-15, "{across}");
    let (_, k) = s.static_frame(x, DVec3::ZERO, (n * f.sqrt() + t).normalize());
    assert!((k - (n + t).normalize()).length() < 1e-15, "{k}");
}

/// Past b = 100 M with no geometry beyond 10 M, the last chord leaves at
/// the periapsis, having turned through only half the deflection; the
/// asymptote follows the rest of the orbit out and meets the series within
/// its tolerance.
#[test]
fn the_asymptote_of_an_escaping_ray_has_turned_through_the_whole_deflection() {
    let b = 100.0;
    let s = hole();
    let origin = Event::new(0.0, s.centre + DVec3::new(1e6, b, 0.0));
    let mut g = Geodesic::backwards(&s, origin, DVec3::NEG_X, LightSpeed::Finite, 10.0);
    assert_eq!(g.asymptote(), None, "not escaped yet");
    let mut last = None;
    for leg in g.by_ref() {
        if let Leg::Chord(ray, _) = leg {
            last = Some(ray.direction.x);
        }
    }
    let alpha = |d: DVec3| math::atan2(-d.y, -d.x);
    let q = M / b;
    let pi = std::f64::consts::PI;
    let series = 4.0 * q
        + 15.0 * pi / 4.0 * q * q
        + 128.0 / 3.0 * q * q * q
        + 3465.0 * pi / 64.0 * q * q * q * q;
    let far = g.asymptote().expect("escaped");
    assert!(
        (alpha(far) - series).abs() < SKY_TOLERANCE + 2e-7,
        "{} vs {series}",
        alpha(far)
    );
    // The control: the last chord itself has turned through about half.
    let chord = alpha(last.unwrap());
    assert!((chord - series / 2.0).abs() < 0.1 * series, "{chord}");
}

/// Told that all geometry lies in a slab the ray crosses after passing
/// the mass, the geodesic takes long steps elsewhere, their chords (meeting
/// nothing) straying farther than the tolerance, but inside the slab its
/// chords keep within it.
#[test]
fn chords_stray_beyond_the_tolerance_only_clear_of_all_geometry() {
    let angle = 1e-3;
    let bound = PIXEL_FRACTION * angle * 130.0;
    let slab = (DVec3::new(-50.0, -1e3, -1e3), DVec3::new(-30.0, 1e3, 1e3));
    let (space, time, n) = worst_stray_in(6.0, 60.0, angle, slab, slab);
    assert!(
        space <= bound && time <= bound,
        "{space}, {time} vs {bound}"
    );
    let everywhere = (DVec3::NEG_INFINITY, DVec3::INFINITY);
    let (_, _, n_everywhere) = worst_stray_in(6.0, 60.0, angle, everywhere, everywhere);
    assert!(
        3 * n < 2 * n_everywhere,
        "{n} chords against {n_everywhere}"
    );
    // Negative control: outside the slab the chords stray beyond the bound.
    let (space, time, _) = worst_stray_in(6.0, 60.0, angle, slab, everywhere);
    assert!(space.max(time) > bound, "{space}, {time} vs {bound}");
}

/// Steps clear of all geometry are long, but their error is held to a
/// fraction of the pixel: the escaping ray's direction meets the one
/// traced with the finest chords to a twentieth of the pixel, from well
/// outside the photon sphere to far out.
#[test]
fn clear_steps_keep_the_deflection_to_a_fraction_of_the_pixel() {
    let s = hole();
    let angle = 2.6e-4;
    let origin = Event::new(10.0, s.centre + DVec3::new(300.0, 0.0, 0.0));
    let nowhere = (DVec3::splat(1e7), DVec3::splat(1e7 + 1.0));
    for b in [10.0, 30.0, 100.0, 250.0] {
        let towards = DVec3::new(-(1.0 - (b / 300.0_f64).powi(2)).sqrt(), b / 300.0, 0.0);
        let sky = |geodesic: Geodesic| {
            let mut geodesic = geodesic;
            let mut n = 0;
            while let Some(Leg::Chord(_, len)) = geodesic.next() {
                n += 1;
                if len.is_infinite() {
                    break;
                }
            }
            (geodesic.asymptote().unwrap(), n)
        };
        let start = || Geodesic::backwards(&s, origin, towards, LightSpeed::Finite, 400.0);
        let (clear, n) = sky(start()
            .sized_to_pixel(angle)
            .with_geometry_in(nowhere.0, nowhere.1));
        let (fine, n_fine) = sky(start());
        let error = clear.angle_between(fine);
        assert!(error < angle / 20.0, "b {b}: {error} rad");
        assert!(4 * n < n_fine, "b {b}: {n} steps against {n_fine}");
    }
}

/// However coarse the pixel (here a 12 x 9 image's, 0.03 rad, from 291 M
/// with a box of geometry beyond the mass), every chord is finite and of
/// positive length, and every ray ends: a footprint larger than the
/// distance to the horizon once gave chords of length 0, whose direction
/// was not a number.
#[test]
fn chords_of_a_coarse_pixel_are_finite_and_every_ray_ends() {
    let s = hole();
    let origin = Event::new(10.0, s.centre + DVec3::new(0.0, 150.0, 250.0));
    let (lo, hi) = (
        DVec3::new(-870.0, -310.0, -830.0),
        DVec3::new(920.0, -90.0, -170.0),
    );
    for i in 0..200 {
        let a = f64::from(i) * 0.0014 - 0.14;
        let towards = (-origin.x + s.centre + DVec3::new(a * 290.0, a * 100.0, 0.0)).normalize();
        let legs: Vec<Leg> = Geodesic::backwards(&s, origin, towards, LightSpeed::Finite, 1500.0)
            .sized_to_pixel(0.031)
            .with_geometry_in(s.centre + lo, s.centre + hi)
            .take(MAX_CHORDS + 2)
            .collect();
        assert!(legs.len() <= MAX_CHORDS + 1, "ray {i} does not end");
        for leg in legs {
            if let Leg::Chord(ray, len) = leg {
                let finite = ray.origin.x.is_finite() && ray.direction.x.is_finite();
                assert!(
                    finite && ray.direction.t.is_finite() && len > 0.0,
                    "ray {i}: {ray:?} {len}"
                );
            }
        }
    }
}
