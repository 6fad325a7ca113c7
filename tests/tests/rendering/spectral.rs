//! Spectral pixels (the Doppler shift on): a uniform background's spectrum
//! found once for the render is the one found ray by ray, to the bit.

use glam::DVec3;
use renderer::{pixel, shader, BackgroundBand, Effects, Frame, Shader, Traversal};
use vstf::{Fixture, Overrides};
use workspace_tests::fixture_with;

/// `doppler` (glowing panels approaching, receding and crossing) at
/// 32 x 24, in front of a blue background, its camera moving with
/// `velocity`.
fn panels(velocity: Option<[f64; 3]>) -> Fixture {
    fixture_with("doppler", |v| {
        v["image"]["width"] = 32.into();
        v["image"]["height"] = 24.into();
        v["image"]["spp"] = 1.into();
        v["image"]["doppler"] = true.into();
        v["background"] = serde_json::json!([0.2, 0.4, 0.7]);
        v.as_object_mut().unwrap().remove("checks");
        if let Some(w) = velocity {
            v["camera"]["velocity"] = serde_json::json!(w);
        }
    })
}

/// Every pixel's bits through `shader`.
fn bits(shader: &Shader, frame: &Frame, (w, h): (u32, u32)) -> Vec<[u64; 3]> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| pixel(shader, frame, x, y).to_array().map(f64::to_bits))
        .collect()
}

/// At rest (the background found once is read) and moving (the observed
/// wavelengths shift ray by ray, so it is not), the pixels are those of
/// a shader that finds the background for every ray. A background changed after the band was found is not read
/// from it (negative control: the band found for blue is not black's).
#[test]
fn a_background_found_once_is_the_one_found_ray_by_ray() {
    for velocity in [None, Some([0.3, 0.0, 0.0])] {
        let f = panels(velocity);
        let view = vstf::run::view(&f, &Overrides::default()).unwrap();
        let db = vstf::run::database(&f, view.model.lorentz, Traversal::Bvh).unwrap();
        let frame = Frame {
            camera: &view.camera,
            camera_t: view.camera_t,
            model: view.model,
            settings: &view.settings,
        };
        let size = (view.camera.width, view.camera.height);
        let once = shader(&db, &f.scene, &frame);
        assert!(once.background_band.is_some());
        let seen = bits(&once, &frame, size);
        let ray_by_ray = Shader {
            background_band: None,
            ..shader(&db, &f.scene, &frame)
        };
        assert!(seen == bits(&ray_by_ray, &frame, size), "{velocity:?}");
        let mut colours = seen.clone();
        colours.sort_unstable();
        colours.dedup();
        assert!(colours.len() > 2, "{velocity:?}: {} colours", colours.len());

        let stale = Shader {
            background: DVec3::ZERO,
            ..shader(&db, &f.scene, &frame)
        };
        let on_black = Shader {
            background: DVec3::ZERO,
            background_band: None,
            ..shader(&db, &f.scene, &frame)
        };
        let on_black = bits(&on_black, &frame, size);
        assert!(bits(&stale, &frame, size) == on_black, "{velocity:?}");
        assert!(on_black != seen, "{velocity:?}: the background shows");
    }
}

/// Rays carry no spectrum without the Doppler shift, and a sky rather
/// than the background: nothing is found for either.
#[test]
fn a_background_band_is_found_only_for_a_spectral_render_without_a_sky() {
    let doppler = Effects {
        doppler: true,
        searchlight: false,
    };
    let blue = DVec3::new(0.2, 0.4, 0.7);
    assert!(BackgroundBand::of(blue, None, doppler).is_some());
    assert!(BackgroundBand::of(blue, None, Effects::NONE).is_none());
    let sky = renderer::Texels::new(1, 1, vec![blue]).unwrap();
    assert!(BackgroundBand::of(blue, Some(&sky), doppler).is_none());
}
