//! Shading (paper 3, item 5): what light a ray brings back from its hit,
//! with shadow and mirror rays on past light cones, and the colour effects
//! of motion (Doppler shift and searchlight, paper 6).

mod bent;
mod carried;
mod doppler;
mod frame;
mod lit;
mod mirror;
mod shader;
mod texture;

pub use bent::BentEnd;
pub use doppler::Effects;
pub use shader::{BackgroundBand, Found, Shader};
