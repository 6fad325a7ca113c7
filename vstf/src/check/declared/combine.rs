//! Readings combined: the ratio of two, and the angle whose tangent one is.

use crate::check::row::Reading;

/// a / b of two independent readings (relative uncertainties in quadrature).
pub(super) fn ratio(a: &Reading, b: &Reading) -> Reading {
    let value = a.value / b.value;
    Reading {
        value,
        tolerance: value.abs() * (a.tolerance / a.value).hypot(b.tolerance / b.value),
    }
}

/// atan(r) in degrees of a ratio, its tolerance carried by d atan / dr =
/// 1 / (1 + r^2).
pub(super) fn atan_degrees(r: &Reading) -> Reading {
    Reading {
        value: r.value.atan().to_degrees(),
        tolerance: (r.tolerance / (1.0 + r.value * r.value)).to_degrees(),
    }
}
