//! `vstf serve`'s page as a user sees it, in a real browser: no image
//! before a view is chosen and none broken after, each image captioned
//! with its fixture, view and model, a speed slider that stops below c,
//! a debug panel that follows the frame, a model menu that names the model
//! rendered after a check; and a screenshot whose render region holds the
//! rendered picture.

use crate::browser::{browser_tools, http, start_browser, start_server, Driver};
use crate::support::Scratch;
use serde_json::json;

/// A square moving at `beta` (a fraction of c) along x, seen from 10
/// units away at t = 10; no views and no checks: `vstf check` compares it
/// with its golden image as its own view, `view`.
fn square_at(beta: f64) -> String {
    format!(
        r#"{{
  "camera": {{"position": [0.0, 0.0, 10.0], "t": 10.0, "look_at": [0.0, 0.0, 0.0], "vfov_deg": 40.0}},
  "light": {{"position": [0.0, 20.0, 20.0], "color": [0.0, 0.0, 0.0], "ambient": 1.0}},
  "background": [0.0, 0.0, 0.0],
  "model": "relativistic",
  "image": {{"width": 64, "height": 48, "spp": 1}},
  "objects": [
    {{"name": "square", "kind": "V_obj",
     "mesh": {{"quad": {{"corner": [-1.0, -1.0, 1.0], "u": [2.0, 0.0, 0.0], "v": [0.0, 2.0, 0.0]}}}},
     "worldline": {{"start": [-50.0, {x0}, 0.0, 0.0], "extrusion": [100.0, {dx}, 0.0, 0.0]}},
     "material": {{"color": [0.2, 0.45, 0.95]}}}}
  ]
}}"#,
        x0 = -50.0 * beta,
        dx = 100.0 * beta
    )
}

/// Standard base64 (the WebDriver screenshot's encoding), decoded.
fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let sextets: Vec<u8> = text.bytes().filter_map(value).collect();
    let mut out = Vec::with_capacity(sextets.len() * 3 / 4);
    for chunk in sextets.chunks(4) {
        let bits = chunk
            .iter()
            .enumerate()
            .fold(0u32, |acc, (i, &s)| acc | u32::from(s) << (18 - 6 * i));
        let bytes = bits.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    out
}

/// Every image on the page: whether it has loaded a picture (complete,
/// with a natural width) and its source attribute.
const IMAGES: &str = "return [...document.images].map(i => \
    ({ok: i.complete && i.naturalWidth > 0, src: i.getAttribute('src')}))";

/// The render's caption, empty while there is none (between a view's
/// choice and its render).
const RENDER_CAPTION: &str =
    "const f = document.getElementById('fig-render'); return f ? f.textContent : ''";

/// The caption of the figure holding image `id`.
fn caption(d: &Driver, id: &str) -> String {
    let js = format!(
        "const f = document.getElementById('fig-{id}'); \
         return f ? f.querySelector('figcaption').textContent : ''"
    );
    d.script(&js).as_str().unwrap_or("").to_string()
}

/// Clicks the list entry of `fixture` / `view` (which clears the render
/// hash) and waits for its render.
fn choose(d: &Driver, fixture: &str, view: &str) {
    d.wait_for(
        "the list",
        "return document.getElementById('fixtures').textContent",
        |v| v.as_str().is_some_and(|s| s.contains(fixture)),
    );
    d.click(&format!("li[data-fixture='{fixture}'][data-view='{view}']"));
    d.wait_for(
        "the render",
        "return document.getElementById('hash').textContent",
        |v| v.as_str().is_some_and(|s| !s.is_empty()),
    );
}

/// The render's pixels as the page decoded them, and where its content
/// box lies in the viewport (CSS pixels), and the device pixel ratio.
const RENDER_PIXELS: &str = "const i = document.getElementById('render'); \
    const c = document.createElement('canvas'); c.width = i.naturalWidth; c.height = i.naturalHeight; \
    const g = c.getContext('2d'); g.drawImage(i, 0, 0); \
    const r = i.getBoundingClientRect(); \
    return {w: c.width, h: c.height, x: r.left + i.clientLeft, y: r.top + i.clientTop, \
      cw: i.clientWidth, vw: innerWidth, vh: innerHeight, dpr: devicePixelRatio, rgba: Array.from(g.getImageData(0, 0, c.width, c.height).data)}";

/// Takes a screenshot and compares the render's region in it with the
/// render's own pixels: how many of the render's pixels the screenshot
/// (of the viewport's size) shows exactly, of how many.
fn screenshot_holds_the_render(d: &Driver) -> (usize, usize) {
    let r = d.script(RENDER_PIXELS);
    let (w, h) = (
        r["w"].as_u64().unwrap() as u32,
        r["h"].as_u64().unwrap() as u32,
    );
    assert_eq!(
        r["dpr"],
        json!(1),
        "a device pixel ratio other than 1: {}",
        r["dpr"]
    );
    assert_eq!(r["cw"].as_u64(), Some(u64::from(w)), "the render is scaled");
    let (x0, y0) = (
        r["x"].as_f64().unwrap().round() as u32,
        r["y"].as_f64().unwrap().round() as u32,
    );
    let rgba: Vec<u8> = r["rgba"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as u8)
        .collect();
    let blank = rgba.chunks(4).all(|p| p == &rgba[..4]);
    assert!(!blank, "the render is one colour");
    let shot = d.call("GET", "/screenshot", None);
    let png = base64(shot.as_str().unwrap());
    assert!(png.starts_with(b"\x89PNG"), "the screenshot is not a PNG");
    let shot = image::load_from_memory(&png).unwrap().to_rgb8();
    let viewport = (r["vw"].as_u64().unwrap(), r["vh"].as_u64().unwrap());
    let size = shot.dimensions();
    assert_eq!(
        (u64::from(size.0), u64::from(size.1)),
        viewport,
        "the screenshot's size"
    );
    let mut same = 0;
    for y in 0..h {
        for x in 0..w {
            let k = 4 * (y * w + x) as usize;
            if shot.get_pixel_checked(x0 + x, y0 + y).map(|p| p.0)
                == Some([rgba[k], rgba[k + 1], rgba[k + 2]])
            {
                same += 1;
            }
        }
    }
    (same, (w * h) as usize)
}

#[test]
fn the_page_captions_its_images_and_bounds_its_sliders_in_a_real_browser() {
    let Some((driver, browser)) = browser_tools() else {
        return;
    };
    let dir = Scratch::new("browser-page");
    std::fs::create_dir_all(dir.join("fixtures")).unwrap();
    std::fs::write(dir.join("fixtures/rod.json"), square_at(0.9)).unwrap();
    std::fs::write(dir.join("fixtures/slow.json"), square_at(0.5)).unwrap();
    std::fs::write(dir.join("fixtures/fast.json"), square_at(0.995)).unwrap();
    let (server, page) = start_server(&dir);
    let (_chromedriver, d) = start_browser(&driver, &browser);
    d.call(
        "POST",
        "/window/rect",
        Some(json!({"width": 1000, "height": 800})),
    );
    d.call("POST", "/url", Some(json!({"url": page})));
    // The fixtures without views are listed with the view check gives them.
    d.wait_for(
        "the list",
        "return document.getElementById('fixtures').textContent",
        |v| {
            v.as_str()
                .is_some_and(|s| s.contains("rod / view — no golden"))
        },
    );
    assert_eq!(
        d.script(IMAGES),
        json!([]),
        "images before a view is chosen"
    );
    choose(&d, "rod", "view");
    let images = d.script(IMAGES);
    let images = images.as_array().unwrap();
    assert_eq!(
        images.len(),
        1,
        "the render only (no golden yet): {images:?}"
    );
    assert!(images.iter().all(|i| i["ok"] == json!(true)), "{images:?}");
    let said = caption(&d, "render");
    assert!(
        said.starts_with("rod / view: render, relativistic model, t = 10")
            && said.contains("speed ×1 (0.9c)"),
        "{said}"
    );
    slider_stops_below_light(&d);
    debug_follows_the_frame(&d);
    model_after_a_check(&d);
    // The screenshot shows the render as the page decoded it, pixel for
    // pixel; the control: the same region of a screenshot after the render
    // is hidden shows almost none of it.
    let (same, of) = screenshot_holds_the_render(&d);
    eprintln!("screenshot: {same} of {of} render pixels shown exactly");
    assert_eq!(same, of, "the screenshot does not show the render");
    d.script("document.getElementById('render').style.visibility = 'hidden'");
    let (hidden, _) = screenshot_holds_the_render(&d);
    eprintln!("with the render hidden: {hidden} of {of}");
    assert!(hidden < of / 2, "{hidden} of {of} with the render hidden");
    let _ = http(&d.addr, "DELETE", &format!("/session/{}", d.session), None);
    drop(server);
}

/// The 0.9c rod's speed slider stops at or below 0.99c whatever is asked
/// of it; the 0.5c square's keeps its ×1.2 (the control); a 0.995c
/// square's stays at ×1, its own speed.
fn slider_stops_below_light(d: &Driver) {
    let top = "const s = document.getElementById('speed'); s.value = 5; \
        s.dispatchEvent(new Event('input')); return Number(s.value)";
    let k = d.script(top).as_f64().unwrap();
    assert!(k > 1.0 && k * 0.9 <= 0.99 + 1e-9, "×{k} of 0.9c");
    d.wait_for("the fastest render", RENDER_CAPTION, |v| {
        v.as_str()
            .is_some_and(|s| s.contains(&format!("speed ×{k}")))
    });
    let status = d.script("return document.getElementById('status').textContent");
    assert_eq!(status, json!(""), "the fastest speed was refused");
    choose(d, "slow", "view");
    let k = d.script(top).as_f64().unwrap();
    assert!((k - 1.2).abs() < 1e-9, "×{k} of 0.5c");
    // An object already past 0.99c is shown at its own speed, not slowed.
    choose(d, "fast", "view");
    assert!(caption(d, "render").contains("speed ×1 (0.995c)"));
    let k = d.script(top).as_f64().unwrap();
    assert!((k - 1.0).abs() < 1e-9, "×{k} of 0.995c");
    choose(d, "rod", "view");
}

/// A clicked pixel's debug variables are traced again when the time
/// slider moves: never those of the frame before.
fn debug_follows_the_frame(d: &Driver) {
    d.click("#render");
    d.wait_for(
        "the debug text",
        "return document.getElementById('debug').textContent",
        |v| v.as_str().is_some_and(|s| s.contains("camera t = 10")),
    );
    let moved = d.script(
        "const s = document.getElementById('t'); s.value = 8; s.dispatchEvent(new Event('input')); \
         return document.getElementById('debug').textContent",
    );
    assert_eq!(moved, json!(""), "the old frame's debug text stayed");
    let now = d.wait_for(
        "the debug text of t = 18",
        "return document.getElementById('debug').textContent",
        |v| v.as_str().is_some_and(|s| s.starts_with("pixel (")),
    );
    let now = now.as_str().unwrap();
    assert!(
        now.contains("camera t = 18") && !now.contains("camera t = 10"),
        "{now}"
    );
}

/// After a check the page shows the view as checked: the menu back on the
/// view's own model (named), the render in it, and the pending image.
fn model_after_a_check(d: &Driver) {
    d.script(
        "const m = document.getElementById('model'); m.value = 'infinite'; m.dispatchEvent(new Event('change'))",
    );
    d.wait_for("the infinite render", RENDER_CAPTION, |v| {
        v.as_str().is_some_and(|s| s.contains("infinite model"))
    });
    d.click("#check");
    d.wait_for(
        "the check",
        "return document.getElementById('status').textContent",
        |v| v.as_str().is_some_and(|s| s.starts_with("rod checked")),
    );
    let menu = d.script(
        "const m = document.getElementById('model'); return [m.value, m.selectedOptions[0].textContent]",
    );
    assert_eq!(menu, json!(["view", "as the view (relativistic)"]));
    d.wait_for("the view's render again", RENDER_CAPTION, |v| {
        v.as_str()
            .is_some_and(|s| s.contains("relativistic model, t = 10"))
    });
    let images = d.wait_for("the pending image", IMAGES, |v| {
        v.as_array()
            .is_some_and(|a| a.len() == 2 && a.iter().all(|i| i["ok"] == json!(true)))
    });
    assert!(caption(d, "diff").contains("no golden yet"), "{images}");
}

/// The `rocket` scene with its camera on keyframes of uniform motion at
/// 0.6c from lab time 2 (its clock runs at 0.8 of lab time), one view at
/// proper time 4 (lab time 7).
fn coasting_rocket() -> String {
    let mut v: serde_json::Value =
        serde_json::from_str(include_str!("../../../fixtures/rocket.json")).unwrap();
    v["camera"]["worldline"] = json!({"keyframes": [
        { "t": 2.0, "position": [0, 0, 0], "velocity": [0, 0, -0.6] },
        { "t": 22.0, "position": [0, 0, -12], "velocity": [0, 0, -0.6] }
    ]});
    v["camera"]["t"] = json!(2.0);
    v["views"] = json!([{ "name": "k", "tau": 4.0 }]);
    v["checks"] = json!([]);
    v.to_string()
}

/// The time slider of a camera on keyframes steps its proper time: moved
/// by 4 from the view's tau = 4, the page shows tau = 8 at the lab time
/// the server read on the camera's clock, 2 + 8 / 0.8 = 12 (the control:
/// not lab time 11, the view's 7 plus 4); the slider stops at the
/// keyframes' last proper time, 16.
#[test]
fn the_time_slider_steps_a_keyframed_cameras_proper_time_in_a_real_browser() {
    let Some((driver, browser)) = browser_tools() else {
        return;
    };
    let dir = Scratch::new("browser-keyframes");
    std::fs::create_dir_all(dir.join("fixtures")).unwrap();
    std::fs::write(dir.join("fixtures/coast.json"), coasting_rocket()).unwrap();
    let (server, page) = start_server(&dir);
    let (_chromedriver, d) = start_browser(&driver, &browser);
    d.call("POST", "/url", Some(json!({"url": page})));
    choose(&d, "coast", "k");
    let said = d.wait_for("the view's render", RENDER_CAPTION, |v| {
        v.as_str().is_some_and(|s| s.contains("τ = 4 (t = 7)"))
    });
    let max = d.script("return Number(document.getElementById('t').max)");
    assert!((max.as_f64().unwrap() - 12.0).abs() < 1e-9, "{max} {said}");
    d.script(
        "const s = document.getElementById('t'); s.value = 4; s.dispatchEvent(new Event('input'));",
    );
    let said = d.wait_for("the later render", RENDER_CAPTION, |v| {
        v.as_str().is_some_and(|s| s.contains("τ = 8"))
    });
    let said = said.as_str().unwrap();
    assert!(
        said.contains("τ = 8 (t = 12)") && !said.contains("t = 11"),
        "{said}"
    );
    let status = d.script("return document.getElementById('status').textContent");
    assert_eq!(status, json!(""));
    let _ = http(&d.addr, "DELETE", &format!("/session/{}", d.session), None);
    drop(server);
}
