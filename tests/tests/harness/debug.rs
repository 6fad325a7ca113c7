//! Debug mode records what rendering computes (debug-diff, which tells
//! two logs apart, in `debug_diff`).

use renderer::{LightSpeed, Traversal};
use renderer::{RayKind, Step};
use vstf::debug::trace_pixel;
use vstf::fixture::{Fixture, Overrides, View};

fn setup(name: &str, w: u32, h: u32) -> (Fixture, View) {
    let f = workspace_tests::fixture(name);
    let view = vstf::run::view(
        &f,
        &Overrides {
            width: Some(w),
            height: Some(h),
            ..Default::default()
        },
    )
    .unwrap();
    (f, view)
}

#[test]
fn the_debugged_colour_is_the_rendered_colour() {
    for name in [
        "teaser",
        "terrell-contracted",
        "flange",
        "doppler",
        "mirror-receding",
    ] {
        let (f, view) = setup(name, 64, 36);
        let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        let image = vstf::run::render_with(&db, &f, &view).unwrap();
        for (x, y) in [(0, 0), (31, 18), (30, 5), (20, 25), (45, 10), (63, 35)] {
            let log = trace_pixel(&f, &view, &db, x, y).unwrap();
            let rendered = image.pixels[(y * 64 + x) as usize];
            assert_eq!(
                log.color.to_array().map(f64::to_bits),
                rendered.to_array().map(f64::to_bits),
                "{name} ({x}, {y})"
            );
        }
    }
}

#[test]
fn the_log_holds_the_variables_along_the_ray() {
    let (f, view) = setup("teaser", 640, 360);
    let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
    // A pixel on the mirror (see the teaser view): a primary hit, a shadow ray, a reflection ray.
    let log = trace_pixel(&f, &view, &db, 300, 60).unwrap();
    let kinds: Vec<RayKind> = log
        .steps
        .iter()
        .filter_map(|s| {
            if let Step::Ray { kind, .. } = s {
                Some(*kind)
            } else {
                None
            }
        })
        .collect();
    assert!(
        kinds.contains(&RayKind::Primary)
            && kinds.contains(&RayKind::Shadow)
            && kinds.contains(&RayKind::Reflection),
        "{kinds:?}"
    );
    assert!(log
        .steps
        .iter()
        .any(|s| matches!(s, Step::Hit { object, .. } if object == "mirror")));
    assert!(log
        .steps
        .iter()
        .any(|s| matches!(s, Step::Candidate { .. })));
    for s in &log.steps {
        if let Step::Ray {
            normalized,
            direction,
            origin,
            ..
        } = s
        {
            assert!(
                abs_diff_eq!(
                    normalized.t,
                    -std::f64::consts::FRAC_1_SQRT_2,
                    epsilon = 1e-12
                ),
                "not on a light cone"
            );
            assert_eq!(direction.t, -1.0);
            assert!(origin.t <= view.camera_t);
        }
        if let Step::Hit {
            event,
            kind: RayKind::Primary,
            ..
        } = s
        {
            let d = *event - view.camera.event;
            assert!(
                abs_diff_eq!(d.interval(), 0.0, epsilon = 1e-9 * d.t * d.t),
                "the primary hit is off the light cone"
            );
        }
    }
    let text = vstf::debug::describe(&log);
    for word in [
        "Primary ray",
        "HIT \"mirror\"",
        "Shadow ray",
        "Reflection ray",
        "shading",
        "n.l =",
        "8-bit",
    ] {
        assert!(text.contains(word), "{word} missing from:\n{text}");
    }
}

#[test]
fn infinite_light_speed_rays_stay_in_the_slice() {
    let f = workspace_tests::fixture("flange");
    let view = vstf::run::view(
        &f,
        &Overrides {
            model: Some(renderer::Model::INFINITE),
            width: Some(64),
            height: Some(48),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(view.model.light_speed, LightSpeed::Infinite);
    let db = vstf::run::database(&f, false, Traversal::Bvh).unwrap();
    let log = trace_pixel(&f, &view, &db, 32, 30).unwrap();
    for s in &log.steps {
        if let Step::Ray { direction, .. } = s {
            assert_eq!(direction.t, 0.0);
        }
        if let Step::Hit { event, .. } = s {
            assert_eq!(event.t, view.camera_t);
        }
    }
}

/// With Doppler on, the log holds each surface's Doppler factors and its
/// spectrum in its own frame, and what the camera records.
#[test]
fn doppler_factors_and_spectra_are_logged() {
    let (f, view) = setup("doppler", 64, 48);
    assert!(
        view.settings.effects.doppler,
        "the fixture renders with Doppler on"
    );
    let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
    let band = renderer::band_nm();
    let mut checked = 0;
    for (x, y) in (0..64).flat_map(|x| (0..48).map(move |y| (x, y))) {
        let log = trace_pixel(&f, &view, &db, x, y).unwrap();
        // The first primary hit, the ray it was found on, and the steps after it.
        let mut ray_dir = None;
        let mut found = None;
        for (i, s) in log.steps.iter().enumerate() {
            match s {
                Step::Ray { direction, .. } => ray_dir = Some(direction.x),
                Step::Hit { object, .. } => {
                    found = Some((ray_dir.unwrap(), object.clone(), i));
                    break;
                }
                _ => {}
            }
        }
        let Some((ray_dir, object, at)) = found else {
            continue;
        };
        let u = f
            .scene
            .objects
            .iter()
            .find(|o| o.name == object)
            .unwrap()
            .motion
            .uniform()
            .unwrap()
            .1;
        let gamma = 1.0 / (1.0 - u.length_squared()).sqrt();
        let expected = 1.0 / (gamma * (1.0 - u.dot(-ray_dir.normalize())));
        let doppler = log.steps[at..].iter().find_map(|s| match s {
            Step::Doppler {
                to_origin,
                surface_nm,
                surface_radiance,
                gamma: g,
                ..
            } => Some((
                *to_origin,
                surface_nm.clone().unwrap(),
                surface_radiance.clone().unwrap(),
                *g,
            )),
            _ => None,
        });
        let (d, nm, radiance, g) = doppler.expect("no Doppler step for a hit");
        assert!(
            abs_diff_eq!(d, expected, epsilon = 1e-12),
            "{object}: D {d} vs {expected}"
        );
        assert_abs_diff_eq!(g, gamma, epsilon = 1e-12);
        assert_eq!(nm.len(), band.len());
        assert_eq!(radiance.len(), band.len());
        for (s, b) in nm.iter().zip(band) {
            assert!(
                abs_diff_eq!(*s, b * d, epsilon = 1e-9),
                "surface-frame wavelengths are the band times D"
            );
        }
        let observed = log.steps[at..].iter().find_map(|s| match s {
            Step::Observed { doppler, xyz, .. } => Some((*doppler, *xyz)),
            _ => None,
        });
        let (f_cam, xyz) = observed.expect("no Observed step");
        assert_eq!(f_cam, 1.0, "the camera is at rest");
        assert!(xyz.unwrap().y > 0.0);
        checked += 1;
    }
    assert!(checked > 20, "only {checked} pixels hit a panel");
}

/// A moving mirror's bounce is logged with its rest-frame directions: there
/// the angles of incidence and reflection are equal, and the lab frequency
/// ratio is Einstein's (1 - 2b cos theta_i + b^2) / (1 - b^2).
#[test]
fn a_moving_mirrors_rest_frame_is_logged() {
    let (f, view) = setup("mirror-approaching", 64, 32);
    let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
    let log = trace_pixel(&f, &view, &db, 44, 16).unwrap();
    let (u, k_out, k_in, ratio, rest) = log
        .steps
        .iter()
        .find_map(|s| match s {
            Step::Reflection {
                mirror_velocity,
                k_out,
                k_in,
                frequency_ratio,
                rest_frame,
                ..
            } => Some((
                *mirror_velocity,
                *k_out,
                *k_in,
                *frequency_ratio,
                *rest_frame,
            )),
            _ => None,
        })
        .expect("no reflection step on the mirror");
    let [n, out, inc] = rest.expect("a mirror at 0.5c has a rest frame");
    assert_abs_diff_eq!(out.dot(n).abs(), inc.dot(n).abs(), epsilon = 1e-12);
    assert!(
        (out.dot(n) * inc.dot(n)) < 0.0,
        "the photon does not turn back"
    );
    let lit = glam::DVec3::Z;
    let b = -u.dot(lit);
    let cos_i = -k_in.dot(lit);
    assert_abs_diff_eq!(
        ratio,
        vstf::oracle::mirror::frequency_ratio(cos_i, b),
        epsilon = 1e-12
    );
    assert!(
        k_out.dot(lit) > 0.0 && (cos_i - k_out.dot(lit)).abs() > 0.05,
        "{cos_i}"
    );
    let text = vstf::debug::describe(&log);
    assert!(
        text.contains("in the mirror's rest frame: normal"),
        "{text}"
    );
}

/// The printout's indentation follows mirror depth: the reflected ray one
/// level in, the mirror's own shading back out at its depth; a hit says
/// from when its proper time counts.
#[test]
fn the_printout_is_indented_by_depth() {
    let (f, view) = setup("teaser", 640, 360);
    let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
    let text = vstf::debug::describe(&trace_pixel(&f, &view, &db, 300, 60).unwrap());
    let line = |start: &str| {
        text.lines()
            .find(|l| l.trim_start().starts_with(start))
            .unwrap_or_else(|| panic!("no {start:?} line in\n{text}"))
    };
    assert!(
        line("Reflection ray (depth 1)").starts_with("    R"),
        "{text}"
    );
    assert!(line("shading (depth 0)").starts_with("  s"), "{text}");
    assert!(
        line("HIT \"mirror\"").contains("since its start at t = -1000000"),
        "{text}"
    );
}

/// The primary `Step::Ray`s of a log (a bent ray's chords): origin,
/// direction and searched range.
fn chords(log: &vstf::debug::PixelLog) -> Vec<(renderer::Event, renderer::FourVector, f64)> {
    log.steps
        .iter()
        .filter_map(|s| match s {
            Step::Ray {
                kind: RayKind::Primary,
                origin,
                direction,
                range,
                ..
            } => Some((*origin, *direction, range.1)),
            _ => None,
        })
        .collect()
}

/// A bent ray's log shows its chords, each starting where the one before
/// ended (in space and coordinate time), and the hit found on the last
/// one searched, within its length; printed, every chord is a line before
/// the hit. A ray into the shadow logs chords and then the black of the
/// hole. The debugged colour is the rendered one, bit for bit.
#[test]
fn a_bent_rays_chords_and_its_hit_are_logged() {
    let (f, view) = setup("black-hole", 240, 180);
    let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
    let image = vstf::run::render_with(&db, &f, &view).unwrap();
    // On the Einstein ring (columns 196..=204 of the middle row).
    let (x, y) = (200, 90);
    let log = trace_pixel(&f, &view, &db, x, y).unwrap();
    let rendered = image.pixels[(y * 240 + x) as usize];
    assert_eq!(log.color.to_array(), rendered.to_array());
    let c = chords(&log);
    assert!(c.len() > 10, "{} chords", c.len());
    for w in c.windows(2) {
        let ((a, d, len), (b, _, _)) = (w[0], w[1]);
        let end = a.x + d.x * len;
        assert!(
            (end - b.x).length() < 1e-9 * (1.0 + a.x.length()),
            "{a:?} {b:?}"
        );
        assert!((a.t + d.t * len - b.t).abs() < 1e-9 * (1.0 + a.t.abs()));
    }
    let hit = log.steps.iter().position(|s| {
        matches!(
            s,
            Step::Hit {
                kind: RayKind::Primary,
                ..
            }
        )
    });
    let Some(Step::Hit { object, event, .. }) = hit.map(|i| &log.steps[i]) else {
        panic!("no hit on the ring: {:?}", log.steps);
    };
    assert_eq!(object, "disc");
    let (origin, d, len) = *c.last().unwrap();
    let s = (event.x - origin.x).dot(d.x);
    assert!(s > 0.0 && s <= len, "hit at {s} on a chord of {len}");
    assert!((origin.x + d.x * s - event.x).length() < 1e-6);
    assert!((origin.t + d.t * s - event.t).abs() < 1e-6);
    let text = vstf::debug::describe(&log);
    let printed_chords = text.lines().filter(|l| l.contains("Primary ray")).count();
    assert_eq!(printed_chords, c.len(), "{text}");
    // The centre of the shadow: chords down to the photon sphere, then black.
    let log = trace_pixel(&f, &view, &db, 120, 90).unwrap();
    assert!(!chords(&log).is_empty());
    assert!(matches!(
        log.steps.last(),
        Some(Step::Miss { background, .. }) if *background == glam::DVec3::ZERO
    ));
    assert_eq!(log.color, glam::DVec3::ZERO);
}

/// With the colour effects on, a bent ray's log holds the gravitational
/// shift between the static observers at the hit and at the camera, the
/// closed form at the hit's radius.
#[test]
fn the_gravitational_shift_is_logged() {
    let (f, view) = setup("redshift-panel", 160, 120);
    let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
    let log = trace_pixel(&f, &view, &db, 80, 60).unwrap();
    let Some(Step::Hit { event, .. }) = log.steps.iter().find(|s| matches!(s, Step::Hit { .. }))
    else {
        panic!("the centre pixel sees the panel");
    };
    let Some(Step::Gravitational {
        emitter_r,
        observer_r,
        factor,
    }) = log
        .steps
        .iter()
        .find(|s| matches!(s, Step::Gravitational { .. }))
    else {
        panic!("no gravitational shift logged: {:?}", log.steps);
    };
    assert!((emitter_r - event.x.length()).abs() < 1e-12);
    assert!((observer_r - 100.0).abs() < 1e-12);
    let expected = vstf::oracle::schwarzschild::static_redshift(1.0, *emitter_r, 100.0);
    assert!((factor - expected).abs() < 1e-12, "{factor} {expected}");
    assert!(vstf::debug::describe(&log).contains("gravitational shift"));
}
