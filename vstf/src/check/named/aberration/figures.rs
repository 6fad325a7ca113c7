//! The paper's figures for the aberration views (4.1.3-4.1.4, Figures
//! 11-16), as a table, and the quantities derived from the silhouette's
//! edges that they are figures of.

use super::cases::{Case, Frame, Seen};
use crate::check::row::{Reading, Unit};
use renderer::Model;

/// Where the control view's right edge lies, degrees: the near face's
/// corner, half a side across at one side's distance, atan(1/2).
fn rest_right() -> f64 {
    (0.5f64).atan().to_degrees()
}

/// Where the control view's right edge lies on the grid 10 l.units ahead:
/// 10 tan(atan 1/2) = 5 grid marks.
const REST_ON_GRID: f64 = 5.0;

/// An azimuth carried onto the grid 10 l.units ahead, grid marks.
fn on_grid(deg: f64) -> f64 {
    10.0 * deg.to_radians().tan()
}

/// A quantity derived from the silhouette's edges, as the paper reports them.
#[derive(Clone, Copy)]
pub(super) enum Derived {
    /// The left edge's azimuth.
    LeftAzimuth,
    /// The right edge's azimuth.
    RightAzimuth,
    /// The right edge on the grid 10 l.units ahead.
    OnGrid,
    /// How far the right edge has moved on the grid from the control view's 5 marks.
    GridShift,
    /// The angle between the left and right edges.
    Subtended,
    /// The right edge's angle from +z, the direction of the Earth's motion
    /// when receding: 180 degrees minus its azimuth.
    FromMotion,
    /// How far the right edge has moved from its control-view azimuth.
    Migration,
}

impl Derived {
    /// The derived value, measured (with its uncertainty) and expected.
    pub(super) fn of(self, seen: &Seen) -> (Reading, f64) {
        let (right, (exp_l, exp_r)) = (seen.right, seen.expected);
        // d(on_grid)/d(deg) = 10 sec^2 * pi / 180.
        let slope =
            10.0 * (1.0 + right.value.to_radians().tan().powi(2)) * std::f64::consts::PI / 180.0;
        let grid = Reading {
            value: on_grid(right.value),
            tolerance: right.tolerance * slope,
        };
        let reading = |value: f64, tolerance: f64| Reading { value, tolerance };
        match self {
            Derived::LeftAzimuth => (seen.left, exp_l),
            Derived::RightAzimuth => (right, exp_r),
            Derived::OnGrid => (grid, on_grid(exp_r)),
            Derived::GridShift => (
                reading(REST_ON_GRID - grid.value, grid.tolerance),
                REST_ON_GRID - on_grid(exp_r),
            ),
            Derived::Subtended => (
                reading(
                    right.value - seen.left.value,
                    right.tolerance.hypot(seen.left.tolerance),
                ),
                exp_r - exp_l,
            ),
            Derived::FromMotion => (reading(180.0 - right.value, right.tolerance), 180.0 - exp_r),
            Derived::Migration => (
                reading(rest_right() - right.value, right.tolerance),
                rest_right() - exp_r,
            ),
        }
    }

    /// The unit of the derived value.
    pub(super) fn unit(self) -> Unit {
        match self {
            Derived::OnGrid | Derived::GridShift => Unit::GridMarks,
            Derived::LeftAzimuth
            | Derived::RightAzimuth
            | Derived::Subtended
            | Derived::FromMotion
            | Derived::Migration => Unit::Degrees,
        }
    }
}

/// A figure the paper prints for one view: the view (season name, speed
/// and model; None for the control view, and for either model), the way
/// it is seen, the quantity's name and what it is, and the figure.
pub(super) struct Figure {
    pub(super) season: Option<&'static str>,
    pub(super) beta: f64,
    pub(super) model: Option<Model>,
    pub(super) frame: Frame,
    pub(super) name: &'static str,
    pub(super) derived: Derived,
    pub(super) paper: f64,
}

impl Figure {
    pub(super) fn applies(&self, case: &Case, frame: Frame) -> bool {
        self.frame == frame
            && self.season == case.season.map(|s| s.name)
            && (case.season.is_none() || self.beta == case.beta)
            && self.model.is_none_or(|m| m == case.model)
    }
}

/// The paper's figures (4.1.3-4.1.4, Figures 11-16). The control view:
/// the right edge at 5 grid marks, a 45 degree silhouette, its right edge
/// 153.4 degrees from +z. Moving left at 0.5c, the right edge migrates by
/// 26.565 degrees (classical: 5 grid marks) or 30 degrees (relativistic:
/// 5.77 marks). Receding at 0.866c the paper prints 93.6 degrees from the
/// direction of motion for the relativistic view; first principles give it
/// to the classical one (docs/physics.md).
pub(super) const FIGURES: &[Figure] = &[
    Figure {
        season: None,
        beta: 0.0,
        model: None,
        frame: Frame::CubeMoving,
        name: "right edge on the grid",
        derived: Derived::OnGrid,
        paper: 5.0,
    },
    Figure {
        season: None,
        beta: 0.0,
        model: None,
        frame: Frame::CubeMoving,
        name: "angle subtended by the silhouette",
        derived: Derived::Subtended,
        paper: 45.0,
    },
    Figure {
        season: None,
        beta: 0.0,
        model: None,
        frame: Frame::CubeMoving,
        name: "right edge angle from +z (receding motion)",
        derived: Derived::FromMotion,
        paper: 153.4,
    },
    Figure {
        season: Some("receding"),
        beta: 0.866,
        model: Some(Model::CLASSICAL),
        frame: Frame::EarthMoving,
        name: "Earth moving: right edge angle from the direction of motion",
        derived: Derived::FromMotion,
        paper: 93.6,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::CLASSICAL),
        frame: Frame::EarthMoving,
        name: "Earth moving: right edge migration",
        derived: Derived::Migration,
        paper: 26.565,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::EarthMoving,
        name: "Earth moving: right edge migration",
        derived: Derived::Migration,
        paper: 30.0,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::CLASSICAL),
        frame: Frame::CubeMoving,
        name: "right edge displacement on the grid",
        derived: Derived::GridShift,
        paper: 5.0,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::CLASSICAL),
        frame: Frame::CubeMoving,
        name: "right edge migration",
        derived: Derived::Migration,
        paper: 26.565,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::CubeMoving,
        name: "right edge displacement on the grid",
        derived: Derived::GridShift,
        paper: 5.77,
    },
    Figure {
        season: Some("moving left"),
        beta: 0.5,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::CubeMoving,
        name: "right edge migration",
        derived: Derived::Migration,
        paper: 30.0,
    },
    Figure {
        season: Some("receding"),
        beta: 0.866,
        model: Some(Model::RELATIVISTIC),
        frame: Frame::CubeMoving,
        name: "right edge angle from the direction of motion",
        derived: Derived::FromMotion,
        paper: 93.6,
    },
];
