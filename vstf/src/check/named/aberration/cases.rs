//! The views of the aberration scene: the seasons of the Earth's motion,
//! the cases rendered (season, speed, model) and what a case's silhouette
//! shows.

use crate::check::row::Reading;
use glam::DVec3;
use renderer::Model;

/// The named kind, prefixing its quantities.
pub(super) const NAME: &str = "aberration";
/// The object measured.
pub(super) const CUBE: &str = "cube";
/// A seasonal view: the Earth's direction of motion.
#[derive(Clone, Copy)]
pub(super) struct Season {
    pub(super) name: &'static str,
    /// Unit vector of the Earth's (observer's) velocity; the star is at -z.
    pub(super) earth: DVec3,
}

pub(super) const SEASONS: [Season; 4] = [
    Season {
        name: "approaching",
        earth: DVec3::NEG_Z,
    },
    Season {
        name: "moving left",
        earth: DVec3::NEG_X,
    },
    Season {
        name: "receding",
        earth: DVec3::Z,
    },
    Season {
        name: "moving right",
        earth: DVec3::X,
    },
];

/// The azimuth of a lab direction from the star (at -z), degrees, positive
/// towards +x.
pub(super) fn azimuth_deg(d: DVec3) -> f64 {
    d.x.atan2(-d.z).to_degrees()
}

/// One view of the cube: the Earth's season at speed `beta` (None: the
/// control view, at rest) under `model`.
#[derive(Clone, Copy)]
pub(super) struct Case {
    pub(super) season: Option<Season>,
    pub(super) beta: f64,
    pub(super) model: Model,
}

impl Case {
    /// The view's name, prefixing its quantities.
    pub(super) fn label(&self) -> String {
        match self.season {
            None => "at rest".into(),
            Some(s) => format!("{} {}c {}", s.name, self.beta, self.model),
        }
    }

    /// Every view in report order: at rest (under the fixture's model),
    /// then each of the `speeds`, model and season.
    pub(super) fn all(base: Model, speeds: &[f64]) -> Vec<Case> {
        let mut cases = vec![Case {
            season: None,
            beta: 0.0,
            model: base,
        }];
        for &beta in speeds {
            for model in [Model::CLASSICAL, Model::RELATIVISTIC] {
                for s in SEASONS {
                    cases.push(Case {
                        season: Some(s),
                        beta,
                        model,
                    });
                }
            }
        }
        cases
    }
}

/// The silhouette's edges on the horizon as measured, and the azimuths
/// (left, right) first principles expect for them.
pub(super) struct Seen {
    pub(super) left: Reading,
    pub(super) right: Reading,
    pub(super) expected: (f64, f64),
}

/// How a season is seen: as the cube moving past the camera at rest, or
/// (the paper's way) as the Earth moving past the cube at rest.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Frame {
    CubeMoving,
    EarthMoving,
}
