//! One line of an object's grid texture, seen on the moving surface (the
//! `grid_line` kind): where its image crosses an image row, or its width
//! there.
//!
//! Measured: the object alone in its own colours (ambient light 1, no
//! lamp, no colour effects), rendered at the view's measuring size; along
//! the row, each pixel's coverage by the line, q = (base - pixel) /
//! (base - line) in the channel where the base and line colours differ
//! most, is summed over the run of covered pixels nearest the expected
//! centre. A pixel's value is the mean of its stratified samples, so the
//! coverage is the fraction of its area the line covers: the line's image
//! between columns a and b gives sum q = b - a (the width) and first moment
//! sum q (i + 1/2) = (b^2 - a^2) / 2, so the centroid is (a + b) / 2 (the
//! centre). Expected: the line's two borders, the rest-frame lines
//! coordinate = k spacing -/+ width / 2 on the surface, each followed on its
//! worldline to where the camera sees it cross the row's centre (the
//! oracle's seen edge); the centre is their mean, the width their distance.

use super::edge::seen_edge;
use crate::check::probe::Effort;
use crate::check::row::{Reading, Unit};
use crate::fixture::checks::{grid_axis, view_size, GridLineSpec, GridRead, ViewSpec};
use crate::measure::Pinhole;
use crate::observer::Observer;
use crate::oracle::Retarded;
use glam::DVec3;
use renderer::{Image, Light, Texture, Traversal};

/// A row's reading, its expectation and unit, and the lab direction to mark.
type Found = ((Reading, f64, Unit), DVec3);

/// The image of one border of the line: its column where it crosses the
/// row's top, centre and bottom, and the lab direction at the centre.
struct Border {
    columns: [f64; 3],
    direction: DVec3,
}

impl Border {
    /// How far the mean of the border's column over the row's height can
    /// lie from its column at the row's centre: c''/24 for a border curved
    /// as c(y), the second difference over half-row steps giving c''/4.
    fn curvature_bias(&self) -> f64 {
        let [top, mid, bottom] = self.columns;
        (top + bottom - 2.0 * mid).abs() / 6.0
    }
}

/// The oracle's image of the rest-frame line `ends` in the row `row` of
/// `camera`'s image.
fn border(
    described: &Observer,
    object: &str,
    ends: [DVec3; 2],
    camera: &Pinhole,
    row: u32,
) -> Result<Border, String> {
    let seen = seen_edge(described, object, ends)?;
    let level_of = |r: &Retarded| camera.pixel_of(r.direction).map(|p| p.1);
    let at = |y: f64| -> Result<(f64, DVec3), String> {
        let (_, r) = seen.crossing(level_of, y).ok_or_else(|| {
            format!("the grid line's image does not cross row {row} (at y = {y:.3} px)")
        })?;
        let (x, _) = camera
            .pixel_of(r.direction)
            .ok_or("the grid line is behind the camera")?;
        Ok((x, r.direction))
    };
    let y = f64::from(row);
    let (top, _) = at(y)?;
    let (mid, direction) = at(y + 0.5)?;
    let (bottom, _) = at(y + 1.0)?;
    Ok(Border {
        columns: [top, mid, bottom],
        direction,
    })
}

/// The object alone in its own colours (ambient 1, no lamp, no colour
/// effects, no shadows or mirrors) from the measuring observer, linear.
fn flat_render(
    measuring: &Observer,
    object: &str,
    size: (u32, u32),
    spp: u32,
) -> Result<std::sync::Arc<Image>, String> {
    let mut probe = measuring
        .fixture
        .only(&[object])
        .map_err(|e| e.to_string())?;
    probe.scene.light = Light {
        position: DVec3::ZERO,
        color: DVec3::ZERO,
        ambient: 1.0,
        spectrum: None,
    };
    let image = &mut probe.spec.image;
    (image.shutter, image.seed, image.max_depth, image.shadows) = (0.0, 1, 0, false);
    (image.doppler, image.searchlight) = (false, false);
    let view = crate::run::view(
        &probe,
        &crate::fixture::Overrides {
            model: Some(measuring.model),
            camera_t: Some(measuring.camera_t),
            width: Some(size.0),
            height: Some(size.1),
            spp: Some(spp),
            ..Default::default()
        },
    )
    .map_err(|e| e.to_string())?;
    crate::run::render_shared(&probe, &view, Traversal::Bvh).map_err(|e| e.to_string())
}

/// The run of pixels of row `row` the line covers nearest `near` (a
/// column), as (width, centroid) in pixels: sum q and sum q (i + 1/2) /
/// sum q. Covered means q of at least half a sample; the run must be
/// bounded on both sides by the surface's own colour (not the background,
/// nor another line along the row), and be at most `longest` pixels.
fn coverage_run(
    img: &Image,
    row: u32,
    (base, line): (DVec3, DVec3),
    near: f64,
    longest: f64,
    spp: u32,
) -> Result<(f64, f64), String> {
    let k = (base - line).abs().max_position();
    let contrast = base[k] - line[k];
    let w = img.width as usize;
    let px = |i: usize| img.pixels[row as usize * w + i];
    let q = |i: usize| (base[k] - px(i)[k]) / contrast;
    let covered = |i: usize| q(i) >= 0.5 / f64::from(spp);
    let centre = (near.floor().max(0.0) as usize).min(w - 1);
    let reach = longest.ceil() as usize + 2;
    let start = (0..=reach)
        .flat_map(|d| [centre.checked_sub(d), Some(centre + d)])
        .flatten()
        .find(|&i| i < w && covered(i))
        .ok_or_else(|| {
            format!("no grid line in row {row} within {reach} px of column {near:.2}")
        })?;
    let (mut lo, mut hi) = (start, start);
    while lo > 0 && covered(lo - 1) {
        lo -= 1;
    }
    while hi + 1 < w && covered(hi + 1) {
        hi += 1;
    }
    let surface = |i: Option<usize>| {
        i.filter(|&i| i < w).is_some_and(|i| {
            (px(i) - base).abs().max_element() <= 0.5 * contrast.abs() / f64::from(spp)
        })
    };
    if !surface(lo.checked_sub(1)) || !surface(Some(hi + 1)) {
        return Err(format!(
            "the grid line in row {row} (columns {lo} to {hi}) is not bounded by the surface's own colour on both sides: it meets the object's border or the background"
        ));
    }
    if (hi - lo + 1) as f64 > longest + 2.0 {
        return Err(format!(
            "the covered run in row {row} is {} px long, more than the line's {longest:.2} px: the row runs along another line of the grid; choose another row",
            hi - lo + 1
        ));
    }
    let (sum, moment) = (lo..=hi).fold((0.0, 0.0), |(s, m), i| {
        (s + q(i), m + q(i) * (i as f64 + 0.5))
    });
    Ok((sum, moment / sum))
}

/// Measures the grid-line check `g`: rendered with `measuring`, expected
/// from `described`.
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    view: &ViewSpec,
    g: &GridLineSpec,
    effort: &Effort,
) -> Result<Found, String> {
    let obj = described.fixture.object(&g.object)?;
    let (axis, _, width) = grid_axis(obj, g.points).map_err(|(f, m)| format!("{f}: {m}"))?;
    let Some(Texture::Grid { color, .. }) = &obj.material.texture else {
        unreachable!("grid_axis found the grid");
    };
    let base = obj.material.color;
    let size = view_size(&described.fixture.spec, view);
    let camera = described.pinhole(size)?;
    let offset = DVec3::from_array(std::array::from_fn(|i| {
        if i == axis {
            width / 2.0
        } else {
            0.0
        }
    }));
    let a = border(
        described,
        &g.object,
        g.points.map(|p| p - offset),
        &camera,
        g.row,
    )?;
    let b = border(
        described,
        &g.object,
        g.points.map(|p| p + offset),
        &camera,
        g.row,
    )?;
    let (ca, cb) = (a.columns[1], b.columns[1]);
    let spp = view.spp.unwrap_or(effort.spp);
    let img = flat_render(measuring, &g.object, size, spp)?;
    let (sum, centroid) = coverage_run(
        &img,
        g.row,
        (base, *color),
        0.5 * (ca + cb),
        (cb - ca).abs(),
        spp,
    )?;
    // The area method resolves each border to 1 / (n sqrt 12) of a pixel
    // with n x n samples (docs/checks.md, edge); the centre is the mean of
    // two borders, the width their difference.
    let n = f64::from(spp).sqrt().round();
    let sigma = 1.0 / (n * 12f64.sqrt());
    let (value, expected, spread, bias) = match g.read {
        GridRead::Centre => (
            centroid,
            0.5 * (ca + cb),
            sigma / 2f64.sqrt(),
            0.5 * (a.curvature_bias() + b.curvature_bias()),
        ),
        GridRead::Width => (
            sum,
            (cb - ca).abs(),
            sigma * 2f64.sqrt(),
            a.curvature_bias() + b.curvature_bias(),
        ),
    };
    let reading = Reading {
        value,
        tolerance: 3.0 * spread + bias,
    };
    Ok((
        (reading, expected, Unit::Pixels),
        a.direction.lerp(b.direction, 0.5),
    ))
}
