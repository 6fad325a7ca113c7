//! The light-speed models of paper 4.1.5 (Figure 1), from two independent
//! switches.

use crate::lightcone::LightSpeed;
use std::fmt;

/// Light speed (infinite | finite) and Lorentz transform (off | on).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Model {
    pub light_speed: LightSpeed,
    /// Whether V_obj objects are Lorentz-transformed on insertion; when off
    /// every object is inserted as an H_obj.
    pub lorentz: bool,
}

impl Model {
    /// Conventional ray tracing of the lab slice t = t_c (Figure 1, top band).
    pub const INFINITE: Model = Model {
        light_speed: LightSpeed::Infinite,
        lorentz: false,
    };
    /// Finite light speed, no Lorentz transform (Figure 1, centre band).
    pub const CLASSICAL: Model = Model {
        light_speed: LightSpeed::Finite,
        lorentz: false,
    };
    /// Finite light speed with the Lorentz transform (Figure 1, bottom band).
    pub const RELATIVISTIC: Model = Model {
        light_speed: LightSpeed::Finite,
        lorentz: true,
    };

    /// `infinite`, `classical` or `relativistic`.
    pub fn from_name(name: &str) -> Option<Model> {
        match name {
            "infinite" => Some(Model::INFINITE),
            "classical" => Some(Model::CLASSICAL),
            "relativistic" => Some(Model::RELATIVISTIC),
            _ => None,
        }
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.light_speed, self.lorentz) {
            (LightSpeed::Infinite, false) => write!(f, "infinite"),
            (LightSpeed::Finite, false) => write!(f, "classical"),
            (LightSpeed::Finite, true) => write!(f, "relativistic"),
            (LightSpeed::Infinite, true) => write!(f, "infinite+lorentz"),
        }
    }
}
