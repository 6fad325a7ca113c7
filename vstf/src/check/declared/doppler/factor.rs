//! A Doppler factor read from pixel values: from a colour, as the shift
//! that gives a blackbody that colour's chromaticity, or from the
//! searchlight's change of brightness; with the uncertainty that half an
//! 8-bit step on each value leaves.

use crate::check::row::Reading;
use crate::measure::colorimetry::{xyz_of_rgb, Blackbody, Chromaticity};
use glam::DVec3;

/// Steps of the scan over the range of factors, evenly spaced in log D.
const SCAN_STEPS: usize = 2700;

/// The scan's `i`-th factor over `(lo, hi)`.
fn grid((lo, hi): (f64, f64), i: usize) -> f64 {
    lo * (hi / lo).powf(i as f64 / SCAN_STEPS as f64)
}

/// The chromaticity of a blackbody shifted by each factor of a scan over a
/// range: they depend on the source and the range alone, so a reading and
/// the readings of its quantisation's eight neighbouring colours share them.
pub(crate) struct ColourScan<'s> {
    source: &'s Blackbody,
    range: (f64, f64),
    chromaticities: Vec<Option<Chromaticity>>,
}

impl<'s> ColourScan<'s> {
    /// The scan of `source` shifted by factors from `lo` to `hi`.
    pub(crate) fn new(source: &'s Blackbody, range: (f64, f64)) -> ColourScan<'s> {
        let chromaticities = (0..=SCAN_STEPS)
            .map(|i| Chromaticity::of(source.xyz_shifted(grid(range, i))))
            .collect();
        ColourScan {
            source,
            range,
            chromaticities,
        }
    }

    /// The factor D by which the source must be shifted (sampled at D
    /// lambda) to have the chromaticity of `rgb`: the scan's nearest, then
    /// golden-section refinement.
    pub(crate) fn factor(&self, rgb: DVec3) -> Option<f64> {
        let target = Chromaticity::of(xyz_of_rgb(rgb))?;
        let distance =
            |c: Option<Chromaticity>| c.map_or(f64::INFINITY, |c| c.distance_squared(target));
        let miss = |d: f64| distance(Chromaticity::of(self.source.xyz_shifted(d)));
        let misses: Vec<f64> = self.chromaticities.iter().map(|&c| distance(c)).collect();
        let best = (0..=SCAN_STEPS)
            .min_by(|&a, &b| misses[a].total_cmp(&misses[b]))
            .unwrap();
        let (mut a, mut b) = (
            grid(self.range, best.saturating_sub(1)),
            grid(self.range, (best + 1).min(SCAN_STEPS)),
        );
        let r = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..80 {
            let (c, d) = (b - r * (b - a), a + r * (b - a));
            if miss(c) < miss(d) {
                b = d;
            } else {
                a = c;
            }
        }
        Some(0.5 * (a + b))
    }
}

/// The largest change of `f(rgb)` when each channel moves by half an 8-bit step.
pub(crate) fn quantisation(rgb: DVec3, f: impl Fn(DVec3) -> Option<f64>) -> f64 {
    let h = 0.5 / 255.0;
    let at = f(rgb).unwrap_or(f64::NAN);
    (0..8)
        .map(|k| {
            let s = |bit: usize| if k >> bit & 1 == 1 { h } else { -h };
            let moved = rgb + DVec3::new(s(0), s(1), s(2));
            (f(moved).unwrap_or(f64::NAN) - at).abs()
        })
        .fold(0.0, f64::max)
}

/// The Doppler factor D read from the searchlight ratio `on / off` = D^power
/// in the brightest channel of `off` (which carries the ratio best), with
/// its uncertainty from half an 8-bit step on each value.
pub(super) fn searchlight_factor(on: DVec3, off: DVec3, power: f64) -> Reading {
    let c = if off.x >= off.y.max(off.z) {
        0
    } else if off.y >= off.z {
        1
    } else {
        2
    };
    let (a, b) = (on[c], off[c]);
    let d = (a / b).powf(1.0 / power);
    let h = 0.5 / 255.0;
    Reading {
        value: d,
        tolerance: d / power * (h / a + h / b),
    }
}
