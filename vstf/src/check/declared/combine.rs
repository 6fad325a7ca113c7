//! Readings combined: the ratio of two, the angle whose tangent one is, and
//! the apparent velocity of two positions measured in different views.

use crate::check::row::{difference, Reading, Unit};

/// A declared check's row, kept for the checks that combine it.
pub(super) struct EarlierRow {
    pub(super) name: String,
    pub(super) measured: Reading,
    pub(super) expected: f64,
    pub(super) unit: Unit,
    /// The camera time of the view measured in (edges and corners).
    pub(super) camera_t: Option<f64>,
}

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

pub(super) fn same_unit(a: &EarlierRow, b: &EarlierRow) -> Result<(), String> {
    if a.unit == b.unit {
        Ok(())
    } else {
        Err(format!(
            "{:?} is in {} and {:?} in {}",
            a.name, a.unit, b.name, b.unit
        ))
    }
}

/// (b - a) / (t_b - t_a) of two positions measured in views at camera times
/// t_a and t_b: an apparent velocity, on a plane or in the image.
pub(super) fn velocity(a: &EarlierRow, b: &EarlierRow) -> Result<(Reading, f64, Unit), String> {
    same_unit(a, b)?;
    let unit = match a.unit {
        Unit::LUnits => Unit::LUnitsPerTUnit,
        Unit::Pixels => Unit::PixelsPerTUnit,
        other => {
            return Err(format!(
                "a velocity needs positions in l.units or px, not {other}"
            ))
        }
    };
    let dt = b
        .camera_t
        .zip(a.camera_t)
        .map(|(tb, ta)| tb - ta)
        .ok_or("a velocity needs two edge or corner checks")?;
    let d = difference(&b.measured, &a.measured);
    let measured = Reading {
        value: d.value / dt,
        tolerance: d.tolerance / dt.abs(),
    };
    Ok((measured, (b.expected - a.expected) / dt, unit))
}
