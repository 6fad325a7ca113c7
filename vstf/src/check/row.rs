//! What a check reports: a measured quantity with its uncertainty, the
//! first-principles value it is held against and the paper's printed
//! figure, judged into a row of the check table.

use crate::fixture::checks::Dimension;
use serde::{Deserialize, Serialize};

/// A value read off the images, with its 3-sigma uncertainty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reading {
    /// The measured value.
    pub value: f64,
    /// Half-width of the band the true value lies in (3 sigma).
    pub tolerance: f64,
}

/// Two independent readings combined as a - b (uncertainties in quadrature).
pub fn difference(a: &Reading, b: &Reading) -> Reading {
    Reading {
        value: a.value - b.value,
        tolerance: a.tolerance.hypot(b.tolerance),
    }
}

/// The unit of a checked quantity, serialised as the check table prints it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Lengths in the scene: light-units (the distance light goes in a t.unit).
    LUnits,
    /// Times in the lab frame, t.units.
    TUnits,
    /// Velocities as a fraction of light speed, l.units per t.unit.
    LUnitsPerTUnit,
    /// Angles on the observer's sky, degrees.
    Degrees,
    /// Positions on the paper's grid 10 l.units ahead, in grid marks.
    GridMarks,
    /// A dimensionless ratio of two lengths.
    Ratio,
    /// A dimensionless factor (the Doppler factor D).
    Factor,
    /// Positions in an image, continuous pixels from its top left corner.
    Pixels,
    /// Apparent velocities in an image, pixels per t.unit of camera time.
    PixelsPerTUnit,
}

impl Unit {
    /// The unit as printed in the table and the JSON rows.
    pub fn as_str(self) -> &'static str {
        match self {
            Unit::LUnits => "l.units",
            Unit::TUnits => "t.units",
            Unit::LUnitsPerTUnit => "l.units/t.unit",
            Unit::Degrees => "deg",
            Unit::GridMarks => "grid marks",
            Unit::Ratio => "ratio",
            Unit::Factor => "factor",
            Unit::Pixels => "px",
            Unit::PixelsPerTUnit => "px/t.unit",
        }
    }
}

impl Unit {
    /// The unit a declared check's row of dimension `d` is given in.
    pub fn of(d: Dimension) -> Unit {
        match d {
            Dimension::Length => Unit::LUnits,
            Dimension::Pixels => Unit::Pixels,
            Dimension::Angle => Unit::Degrees,
            Dimension::Ratio => Unit::Ratio,
            Dimension::Factor => Unit::Factor,
            Dimension::Time => Unit::TUnits,
            Dimension::Speed => Unit::LUnitsPerTUnit,
            Dimension::PixelSpeed => Unit::PixelsPerTUnit,
        }
    }

    /// Every unit.
    pub const ALL: [Unit; 9] = [
        Unit::LUnits,
        Unit::TUnits,
        Unit::LUnitsPerTUnit,
        Unit::Degrees,
        Unit::GridMarks,
        Unit::Ratio,
        Unit::Factor,
        Unit::Pixels,
        Unit::PixelsPerTUnit,
    ];
}

impl<'de> Deserialize<'de> for Unit {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Unit, D::Error> {
        let s = String::deserialize(d)?;
        Unit::ALL
            .into_iter()
            .find(|u| u.as_str() == s)
            .ok_or_else(|| serde::de::Error::custom(format!("unknown unit {s:?}")))
    }
}

impl Serialize for Unit {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl std::fmt::Display for Unit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One quantity of a check's table: what was measured, what first
/// principles expect, and the figure the paper prints, if any.
#[derive(Clone, Debug, PartialEq)]
pub struct Quantity {
    /// What is measured, as the table names it.
    pub name: String,
    /// The value read off the images and its uncertainty.
    pub measured: Reading,
    /// The first-principles value ([`crate::oracle`]).
    pub expected: f64,
    /// The paper's printed figure, where it gives one.
    pub paper: Option<f64>,
    /// The unit of all three.
    pub unit: Unit,
    /// Why the quantity could not be measured, if it could not: its row
    /// fails with this message and no numbers.
    pub error: Option<String>,
}

impl Quantity {
    /// The quantity `name` (in `unit`, when its kind has one) that could not
    /// be measured, for the reason `message`.
    pub fn failed(name: &str, unit: Unit, message: String) -> Quantity {
        Quantity {
            name: name.into(),
            measured: Reading {
                value: f64::NAN,
                tolerance: f64::NAN,
            },
            expected: f64::NAN,
            paper: None,
            unit,
            error: Some(message),
        }
    }

    /// The quantity judged for `fixture`: it passes when the measurement and
    /// its tolerance are finite and the measurement lies within the
    /// tolerance of the expectation.
    pub fn judge(self, fixture: &str) -> Row {
        let Reading { value, tolerance } = self.measured;
        Row {
            fixture: fixture.into(),
            quantity: self.name,
            measured: value,
            expected: self.expected,
            paper: self.paper,
            tolerance,
            unit: self.unit,
            pass: self.error.is_none()
                && value.is_finite()
                && tolerance.is_finite()
                && (value - self.expected).abs() <= tolerance,
            error: self.error,
            camera_t: None,
        }
    }
}

/// One checked quantity, as the table and the JSON rows show it. A row
/// that could not be measured has no numbers (NaN here, `null` in JSON),
/// fails, and carries its `error`; the key is absent from other rows.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct Row {
    /// The fixture checked.
    pub fixture: String,
    /// What was measured.
    pub quantity: String,
    /// The value read off the images.
    #[serde(deserialize_with = "number_or_null")]
    pub measured: f64,
    /// The first-principles value.
    #[serde(deserialize_with = "number_or_null")]
    pub expected: f64,
    /// The paper's printed figure, where it gives one.
    pub paper: Option<f64>,
    /// How far the measurement may lie from the expectation (3 sigma).
    #[serde(deserialize_with = "number_or_null")]
    pub tolerance: f64,
    /// The unit of the values.
    pub unit: Unit,
    /// Whether the measurement lies within the tolerance.
    pub pass: bool,
    /// Why the quantity could not be measured, if it could not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The camera time of the view measured in, where the view's `t` was
    /// solved (`auto`, `auto:OBJECT`, `seen_at_azimuth`) rather than given
    /// as a number; the key is absent from other rows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_t: Option<f64>,
}

/// A number, or NaN where JSON has `null` (as serde_json writes a NaN).
fn number_or_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

impl Row {
    /// Whether the paper's figure lies outside the tolerance around the
    /// first-principles value (explained in docs/physics.md).
    pub fn paper_disagrees(&self) -> bool {
        self.paper
            .is_some_and(|p| (p - self.expected).abs() > self.tolerance)
    }
}
