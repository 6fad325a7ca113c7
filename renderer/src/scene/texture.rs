//! Surface textures: a colour that varies over an object's surface.
//!
//! Procedural patterns are functions of the point in the object's own frame
//! (its rest frame, relative to its reference point), so that the pattern is
//! painted on the object: a moving object carries it along, and its image
//! shows the pattern Lorentz-contracted, light-delayed and aberrated like
//! the rest of the object. Image textures are looked up by texture
//! coordinates (u, v), given per triangle corner for a mesh, or by the
//! direction from the centre for an analytic sphere (equirectangular).

use crate::math;
use glam::{DVec2, DVec3};
use std::fmt;
use std::sync::Arc;

/// Which of the object's axes a procedural pattern varies along; a surface
/// lying in a plane of constant x (y, z) takes a pattern that does not vary
/// along x (y, z), or every point of it would sit on one cell wall.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Axes(pub [bool; 3]);

impl Axes {
    /// All three axes.
    pub const XYZ: Axes = Axes([true; 3]);

    fn chosen(self, p: DVec3) -> impl Iterator<Item = f64> {
        let c = p.to_array();
        (0..3).filter(move |&i| self.0[i]).map(move |i| c[i])
    }
}

/// A colour pattern over a surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// Cells of side `size` (object frame, l.units) along the chosen axes,
    /// alternating `colors[0]` and `colors[1]`: the cell holding the origin
    /// on its low corner takes `colors[0]`, and each step of one cell along
    /// a chosen axis swaps the colour.
    Checkerboard {
        /// Side of a cell, l.units.
        size: f64,
        /// The two colours, linear RGB.
        colors: [DVec3; 2],
        /// The axes along which the cells alternate.
        axes: Axes,
    },
    /// Lines `color` over the material's own colour: the points within
    /// `width / 2` of a plane x = k * spacing (k an integer), and likewise
    /// for each chosen axis, in the object frame.
    Grid {
        /// Distance between neighbouring lines, l.units.
        spacing: f64,
        /// Full width of a line, l.units.
        width: f64,
        /// The lines' colour, linear RGB.
        color: DVec3,
        /// The axes whose constant planes draw lines.
        axes: Axes,
    },
    /// An image multiplying the material's colour, bilinearly filtered,
    /// repeating beyond [0, 1].
    Image {
        /// The image, linear RGB.
        texels: Arc<Texels>,
        /// Where each surface point is in the image.
        mapping: UvMapping,
    },
}

/// How a surface point finds its texture coordinates (u right, v down the
/// image, [0, 1] across it).
#[derive(Clone, Debug, PartialEq)]
pub enum UvMapping {
    /// Per triangle of the mesh, the coordinates of its three corners, in
    /// the order of the triangle's vertices; a point takes its barycentric
    /// mix of them.
    Corners(Vec<[DVec2; 3]>),
    /// Longitude and latitude of the direction from the object's reference
    /// point: u = 1/2 + atan2(x, z) / 2 pi (u = 1/2 facing +z, growing
    /// towards +x), v = acos(y / r) / pi (0 at the +y pole).
    Equirectangular,
}

/// An image of linear RGB texels, row by row from the top.
#[derive(Clone, PartialEq)]
pub struct Texels {
    width: u32,
    height: u32,
    linear: Vec<DVec3>,
}

impl fmt::Debug for Texels {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Texels({} x {})", self.width, self.height)
    }
}

impl Texels {
    /// The image of `width` x `height` texels, row by row from the top;
    /// `None` unless there are width * height > 0 of them.
    pub fn new(width: u32, height: u32, linear: Vec<DVec3>) -> Option<Texels> {
        let n = (width as usize).checked_mul(height as usize)?;
        (n > 0 && linear.len() == n).then_some(Texels {
            width,
            height,
            linear,
        })
    }

    /// Width and height in texels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn at(&self, x: i64, y: i64) -> DVec3 {
        let (w, h) = (i64::from(self.width), i64::from(self.height));
        self.linear[(y.rem_euclid(h) * w + x.rem_euclid(w)) as usize]
    }

    /// The colour of an equirectangular image (a sky at infinity) in the
    /// direction `d`, as [`UvMapping::Equirectangular`] maps it: the
    /// image's centre is +z, its left and right edges -z, its top row +y,
    /// and u grows towards +x; bilinear, as [`Texels::bilinear`].
    pub fn toward(&self, d: DVec3) -> DVec3 {
        self.bilinear(equirectangular(d))
    }

    /// The colour at (u, v), bilinear between the four nearest texel
    /// centres (texel i's centre at u = (i + 1/2) / width), repeating.
    pub fn bilinear(&self, uv: DVec2) -> DVec3 {
        if !uv.is_finite() {
            return DVec3::NAN;
        }
        let x = uv.x * f64::from(self.width) - 0.5;
        let y = uv.y * f64::from(self.height) - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (i, j) = (x0 as i64, y0 as i64);
        let top = self.at(i, j) * (1.0 - fx) + self.at(i + 1, j) * fx;
        let bottom = self.at(i, j + 1) * (1.0 - fx) + self.at(i + 1, j + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

/// Where on its object a surface point is: what a texture is evaluated at.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SurfacePoint {
    /// The point in the object's own frame, relative to its reference point.
    pub(crate) local: DVec3,
    /// The mesh triangle and the point's barycentric coordinates over its
    /// vertices, when known.
    pub(crate) corners: Option<(u32, [f64; 3])>,
}

impl Texture {
    /// The colour at `p` over the material colour `base`; `None` where an
    /// image has no coordinates for the point (the base colour shows).
    pub(crate) fn color(&self, base: DVec3, p: &SurfacePoint) -> Option<DVec3> {
        match self {
            Texture::Checkerboard { size, colors, axes } => {
                let cells: f64 = axes.chosen(p.local).map(|c| (c / size).floor()).sum();
                Some(colors[usize::from(cells.rem_euclid(2.0) != 0.0)])
            }
            Texture::Grid {
                spacing,
                width,
                color,
                axes,
            } => {
                let on = axes.chosen(p.local).any(|c| {
                    let off = c - (c / spacing).round() * spacing;
                    off.abs() <= 0.5 * width
                });
                Some(if on { *color } else { base })
            }
            Texture::Image { texels, mapping } => {
                let uv = mapping.uv(p)?;
                Some(base * texels.bilinear(uv))
            }
        }
    }
}

/// The equirectangular coordinates of the direction `d` (any length):
/// u = 1/2 + atan2(x, z) / 2 pi, v = acos(y / |d|) / pi.
fn equirectangular(d: DVec3) -> DVec2 {
    let d = d.normalize_or_zero();
    let u = 0.5 + math::atan2(d.x, d.z) / std::f64::consts::TAU;
    let v = math::acos(d.y.clamp(-1.0, 1.0)) / std::f64::consts::PI;
    DVec2::new(u, v)
}

impl UvMapping {
    fn uv(&self, p: &SurfacePoint) -> Option<DVec2> {
        match self {
            UvMapping::Corners(corners) => {
                let (t, b) = p.corners?;
                let c = corners.get(t as usize)?;
                Some(c[0] * b[0] + c[1] * b[1] + c[2] * b[2])
            }
            UvMapping::Equirectangular => Some(equirectangular(p.local)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(local: DVec3) -> SurfacePoint {
        SurfacePoint {
            local,
            corners: None,
        }
    }

    #[test]
    fn a_checkerboard_alternates_cell_by_cell_along_the_chosen_axes() {
        let (a, b) = (DVec3::X, DVec3::Y);
        let t = Texture::Checkerboard {
            size: 0.5,
            colors: [a, b],
            axes: Axes([true, true, false]),
        };
        let c = |x, y, z| t.color(DVec3::ZERO, &at(DVec3::new(x, y, z))).unwrap();
        assert_eq!(c(0.1, 0.1, 0.0), a);
        assert_eq!(c(0.6, 0.1, 0.0), b);
        assert_eq!(c(0.6, 0.6, 0.0), a);
        assert_eq!(
            c(-0.1, 0.1, 0.0),
            b,
            "the cell below zero is the other colour"
        );
        assert_eq!(c(0.1, 0.1, 7.3), a, "z is not a chosen axis");
    }

    #[test]
    fn grid_lines_have_their_width_around_multiples_of_the_spacing() {
        let t = Texture::Grid {
            spacing: 1.0,
            width: 0.1,
            color: DVec3::ONE,
            axes: Axes([true, false, false]),
        };
        let base = DVec3::new(0.2, 0.3, 0.4);
        let c = |x| t.color(base, &at(DVec3::new(x, 0.5, 0.5))).unwrap();
        assert_eq!(c(2.04), DVec3::ONE);
        assert_eq!(c(-0.96), DVec3::ONE);
        assert_eq!(c(2.06), base);
        assert_eq!(c(0.5), base);
    }

    #[test]
    fn bilinear_filtering_meets_texel_centres_and_mixes_between() {
        let t = Texels::new(2, 1, vec![DVec3::ZERO, DVec3::ONE]).unwrap();
        assert_eq!(t.bilinear(DVec2::new(0.25, 0.5)), DVec3::ZERO);
        assert_eq!(t.bilinear(DVec2::new(0.75, 0.5)), DVec3::ONE);
        assert_eq!(t.bilinear(DVec2::new(0.5, 0.5)), DVec3::splat(0.5));
        assert_eq!(
            t.bilinear(DVec2::new(1.0, 0.5)),
            DVec3::splat(0.5),
            "repeats"
        );
        assert!(Texels::new(2, 2, vec![DVec3::ZERO; 3]).is_none());
        assert!(Texels::new(0, 0, vec![]).is_none());
    }

    #[test]
    fn the_equirectangular_map_faces_plus_z_at_its_centre() {
        let uv = |d: DVec3| UvMapping::Equirectangular.uv(&at(d)).unwrap();
        assert_eq!(uv(DVec3::Z * 2.0), DVec2::new(0.5, 0.5));
        assert_eq!(uv(DVec3::Y).y, 0.0);
        assert!((uv(DVec3::X).x - 0.75).abs() < 1e-15);
    }

    #[test]
    fn corner_coordinates_mix_by_barycentric_weights() {
        let m = UvMapping::Corners(vec![[DVec2::ZERO, DVec2::X, DVec2::Y]]);
        let p = SurfacePoint {
            local: DVec3::ZERO,
            corners: Some((0, [0.5, 0.25, 0.25])),
        };
        assert_eq!(m.uv(&p), Some(DVec2::new(0.25, 0.25)));
        let beyond = SurfacePoint {
            corners: Some((1, [1.0, 0.0, 0.0])),
            ..p
        };
        assert_eq!(m.uv(&beyond), None);
    }
}
