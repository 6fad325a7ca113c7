//! A second, deliberately naive oracle for whole images: the slice-by-slice
//! method of Hornof et al. ("A snapshot of relativistic motion: visualizing
//! the Terrell-Penrose effect", Communications Physics 8, 161, 2025), who
//! photographed fast objects without moving them fast.
//!
//! The object stands still, already Lorentz-contracted. A light pulse and a
//! gated camera pick out one slice of it: the surface points whose distance
//! from the camera lies in the gate [d, d + dz). For each slice the object
//! is first moved by the distance it would have covered, x = x0 + v t with
//! t = tc - (d + dz/2), the time the middle of the slice's light left it
//! (the paper's dx = beta dz between consecutive slices). The snapshot is
//! the slices composited: each point of the surface is recorded where it
//! stood in every slice whose gate admits it, and each part of the image
//! shows the nearest point recorded there. As dz -> 0 this is the camera's
//! past light cone, reached by a route that shares nothing with the
//! renderer: no extrusion, no tetrahedra, no rays in 4D, no hierarchy, only
//! surface points of static shapes, their distances and their projections.
//!
//! Points, not rays: a line of sight grazing a surface that moves across it
//! meets the surface, slice after slice, at distances that jump by more
//! than a slice (the surface's apparent speed along the line of sight
//! exceeds c), so ray-casting each slice would see it in stripes. A point's
//! distance changes by (1 + u.e) dz from one slice to the next (e the unit
//! vector from the camera), less than 2 dz, so every point is recorded in
//! about 1 / (1 + u.e) slices; the surface is sampled densely enough that
//! every image cell gets points.
//!
//! The camera is the measurements' own pinhole ([`crate::measure::Pinhole`]);
//! each body's class (its index) is what an image cell shows.

use crate::measure::Pinhole;
use crate::oracle::gamma;
use glam::DVec3;

/// What a body is made of, relative to its reference point, as it stands
/// in the lab (already contracted).
#[derive(Clone, Debug)]
pub(crate) enum Form {
    /// Triangles.
    Triangles(Vec<[DVec3; 3]>),
    /// A sphere of rest radius `radius` contracted by 1/gamma along `axis`
    /// (unit): an ellipsoid.
    Ellipsoid {
        /// Rest radius.
        radius: f64,
        /// The unit direction of the motion.
        axis: DVec3,
        /// The contraction factor's inverse.
        gamma: f64,
    },
}

/// One moving body: its form, where its reference point is at `t0` and its
/// lab velocity.
#[derive(Clone, Debug)]
pub(crate) struct Body {
    /// The body's shape about its reference point.
    pub form: Form,
    /// Lab time of `x0`.
    pub t0: f64,
    /// The reference point at `t0`.
    pub x0: DVec3,
    /// Lab velocity, fraction of c.
    pub velocity: DVec3,
}

impl Body {
    /// The radius about the reference point that holds the body.
    pub(crate) fn reach(&self) -> f64 {
        match &self.form {
            Form::Triangles(t) => t.iter().flatten().map(|p| p.length()).fold(0.0, f64::max),
            Form::Ellipsoid { radius, .. } => *radius,
        }
    }

    /// A sphere of rest radius `radius` moving with `velocity`, contracted
    /// when `contracted`.
    pub(crate) fn sphere(
        radius: f64,
        t0: f64,
        x0: DVec3,
        velocity: DVec3,
        contracted: bool,
    ) -> Body {
        let speed = velocity.length();
        let form = Form::Ellipsoid {
            radius,
            axis: velocity.try_normalize().unwrap_or(DVec3::X),
            gamma: if contracted { gamma(speed) } else { 1.0 },
        };
        Body {
            form,
            t0,
            x0,
            velocity,
        }
    }

    /// Points covering the body's surface at most `spacing` apart,
    /// relative to its reference point, each handed to `visit` as it is
    /// made (there are millions: kept, they would cost more to page in
    /// than to use).
    fn each_surface_point(&self, spacing: f64, mut visit: impl FnMut(DVec3)) {
        match &self.form {
            Form::Triangles(tris) => {
                for t in tris {
                    triangle_points(t, spacing, &mut visit);
                }
            }
            Form::Ellipsoid {
                radius,
                axis,
                gamma,
            } => {
                // The rest sphere in latitude rings about the axis, each ring
                // as finely divided as its circumference needs; then contracted.
                let (u, w) = perpendiculars(*axis);
                let rings = ((std::f64::consts::PI * radius / spacing).ceil() as usize).max(2);
                for i in 0..=rings {
                    let theta = std::f64::consts::PI * i as f64 / rings as f64;
                    let (along, across) = (radius * theta.cos(), radius * theta.sin());
                    let around =
                        ((std::f64::consts::TAU * across / spacing).ceil() as usize).max(1);
                    for j in 0..around {
                        let phi = std::f64::consts::TAU * j as f64 / around as f64;
                        visit(*axis * (along / gamma) + (u * phi.cos() + w * phi.sin()) * across);
                    }
                }
            }
        }
    }
}

/// Two unit vectors perpendicular to the unit `a` and to each other.
fn perpendiculars(a: DVec3) -> (DVec3, DVec3) {
    let helper = if a.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let u = a.cross(helper).normalize();
    (u, a.cross(u))
}

/// A triangular grid of points over triangle `t`, at most `spacing` apart,
/// each handed to `visit`.
fn triangle_points(t: &[DVec3; 3], spacing: f64, visit: &mut impl FnMut(DVec3)) {
    let longest = (t[1] - t[0])
        .length()
        .max((t[2] - t[1]).length())
        .max((t[0] - t[2]).length());
    let m = ((longest / spacing).ceil() as usize).max(1);
    for i in 0..=m {
        for j in 0..=(m - i) {
            let (a, b) = (i as f64 / m as f64, j as f64 / m as f64);
            visit(t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b);
        }
    }
}

/// The gate's slices: `count` of thickness `thickness` from distance `near`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Gate {
    /// Distance from the camera where the first slice begins.
    pub near: f64,
    /// Thickness of each slice, l.units (the paper's dz).
    pub thickness: f64,
    /// Number of slices.
    pub count: usize,
}

/// The composited snapshot of `bodies` from a camera at rest at `camera`
/// at lab time `tc`.
pub(crate) struct Snapshot<'a> {
    /// The bodies, each its own class.
    pub bodies: &'a [Body],
    /// The camera's position.
    pub camera: DVec3,
    /// The camera's lab time.
    pub tc: f64,
    /// The slices.
    pub gate: Gate,
}

impl Snapshot<'_> {
    /// The lab time the middle of slice `k`'s light left.
    fn slice_time(&self, k: f64) -> f64 {
        self.tc - (self.gate.near + (k + 0.5) * self.gate.thickness)
    }

    /// Where the point at `p` (relative to body `b`'s reference point)
    /// stands for slice `k`.
    fn placed(&self, b: &Body, p: DVec3, k: f64) -> DVec3 {
        b.x0 + b.velocity * (self.slice_time(k) - b.t0) + p
    }

    /// How far a point at distance `rho` from the camera lies beyond slice
    /// `k`'s near end.
    fn depth_at(&self, rho: f64, k: f64) -> f64 {
        rho - (self.gate.near + k * self.gate.thickness)
    }

    /// How far the point at `p`, placed as for slice `k`, lies beyond the
    /// slice's near end: strictly decreasing in k, since the point's
    /// distance changes by less than dz per slice (|v| < 1) while the gate
    /// moves by dz.
    fn depth_in(&self, b: &Body, p: DVec3, k: usize) -> f64 {
        let rho = self.placed(b, p, k as f64).distance(self.camera);
        self.depth_at(rho, k as f64)
    }

    /// The first slice whose gate admits the point at `p` (depth below dz),
    /// with where the point stands for it and its distance from the camera;
    /// or `count` if none: `guess` itself where it admits the point and the
    /// slice before does not (most often, for a neighbour's slice);
    /// otherwise predicted from the depths at `guess` and the next slice
    /// (the depth is nearly linear in k), then settled by stepping, so the
    /// answer rests on the depths of whole slices alone.
    fn first_slice(&self, b: &Body, p: DVec3, guess: usize) -> (usize, Option<(DVec3, f64)>) {
        let (dz, count) = (self.gate.thickness, self.gate.count);
        let g = guess.min(count - 1);
        let at = self.placed(b, p, g as f64);
        let rho = at.distance(self.camera);
        let here = self.depth_at(rho, g as f64);
        if here < dz && (g == 0 || self.depth_in(b, p, g - 1) >= dz) {
            return (g, Some((at, rho)));
        }
        let next = self.depth_in(b, p, g + 1);
        let step = here - next;
        let mut k = if step > 0.0 && step.is_finite() {
            let predicted = (g as f64 + (here - dz) / step).clamp(0.0, (count - 1) as f64);
            // Rounded up (as an integer conversion and a comparison, where
            // `ceil` is a library call on the baseline x86-64).
            let below = predicted as usize;
            below + usize::from((below as f64) < predicted)
        } else {
            g
        };
        while k > 0 && self.depth_in(b, p, k - 1) < dz {
            k -= 1;
        }
        while k < count {
            let at = self.placed(b, p, k as f64);
            let rho = at.distance(self.camera);
            if self.depth_at(rho, k as f64) >= dz {
                k += 1;
                continue;
            }
            return (k, Some((at, rho)));
        }
        (k, None)
    }

    /// The image of the bodies in cells of 1/`n` pixel: for each cell of the
    /// (w n) x (h n) grid, row by row, the class of the nearest point
    /// recorded there, or `None`. `spacing` is how far apart the surface
    /// points are taken.
    pub(crate) fn cells(
        &self,
        camera: &Pinhole,
        (w, h): (u32, u32),
        n: u32,
        spacing: f64,
    ) -> Vec<Option<usize>> {
        let (cw, ch) = (w * n, h * n);
        if self.gate.count == 0 {
            return vec![None; (cw * ch) as usize];
        }
        let mut nearest: Vec<(f64, Option<usize>)> =
            vec![(f64::INFINITY, None); (cw * ch) as usize];
        let dz = self.gate.thickness;
        for (class, b) in self.bodies.iter().enumerate() {
            // Neighbouring points enter the gate in neighbouring slices.
            let mut guess = self.gate.count / 2;
            b.each_surface_point(spacing, |p| {
                let (first, mut placed) = self.first_slice(b, p, guess);
                guess = first;
                // The slices whose gate admits the point: depth in [0, dz).
                for k in first..self.gate.count {
                    let (at, rho) = placed.take().unwrap_or_else(|| {
                        let at = self.placed(b, p, k as f64);
                        (at, at.distance(self.camera))
                    });
                    let depth = self.depth_at(rho, k as f64);
                    if depth.is_nan() || depth < 0.0 {
                        break;
                    }
                    if depth >= dz {
                        continue;
                    }
                    let Some((px, py)) = camera.pixel_of((at - self.camera) / rho) else {
                        continue;
                    };
                    // The cell's column and row: the integer parts of (cx, cy),
                    // which are not negative once past this test.
                    let (cx, cy) = (px * f64::from(n), py * f64::from(n));
                    if cx < 0.0 || cy < 0.0 || cx >= f64::from(cw) || cy >= f64::from(ch) {
                        continue;
                    }
                    let cell = &mut nearest[(cy as u32 * cw + cx as u32) as usize];
                    if rho < cell.0 {
                        *cell = (rho, Some(class));
                    }
                }
            });
        }
        nearest.into_iter().map(|(_, c)| c).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square 10 l.units ahead, at rest and crossing at 0.8c: at
    /// rest it covers the image centre; moving, it is seen where its light
    /// left it, 0.8 times its light time back along its motion.
    #[test]
    fn slices_shift_the_body_by_its_light_time() {
        let square = Form::Triangles(vec![
            [
                DVec3::new(-0.5, -0.5, 0.0),
                DVec3::new(0.5, -0.5, 0.0),
                DVec3::new(0.5, 0.5, 0.0),
            ],
            [
                DVec3::new(-0.5, -0.5, 0.0),
                DVec3::new(0.5, 0.5, 0.0),
                DVec3::new(-0.5, 0.5, 0.0),
            ],
        ]);
        let body = |v: f64| Body {
            form: square.clone(),
            t0: 0.0,
            x0: DVec3::new(0.0, 0.0, -10.0),
            velocity: DVec3::new(v, 0.0, 0.0),
        };
        let camera =
            Pinhole::looking_at(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, 40.0, (40, 40)).unwrap();
        let gate = Gate {
            near: 9.0,
            thickness: 0.01,
            count: 200,
        };
        let centre_class = |bodies: &[Body], tc: f64| {
            let snap = Snapshot {
                bodies,
                camera: DVec3::ZERO,
                tc,
                gate,
            };
            snap.cells(&camera, (40, 40), 1, 0.01)[20 * 40 + 20]
        };
        assert_eq!(centre_class(&[body(0.0)], 10.0), Some(0));
        // Light leaving at t = 0 arrives at tc = 10: the square is centred.
        assert_eq!(centre_class(&[body(0.8)], 10.0), Some(0));
        // At tc = 15 it was seen 4 to the right of the axis: the centre is empty.
        assert_eq!(centre_class(&[body(0.8)], 15.0), None);
    }

    /// The first admitted slice does not depend on the guess it starts
    /// from, and is the one a scan of every slice finds, for points seen
    /// approaching and receding at 0.999c and for points never admitted.
    #[test]
    fn first_slice_is_the_scans_whatever_the_guess() {
        let gate = Gate {
            near: 8.0,
            thickness: 0.01,
            count: 400,
        };
        for v in [-0.999, -0.5, 0.0, 0.5, 0.999] {
            let body = Body {
                form: Form::Triangles(Vec::new()),
                t0: 0.0,
                x0: DVec3::new(0.0, 0.0, -10.0),
                velocity: DVec3::new(v, 0.0, 0.3 * v),
            };
            let snap = Snapshot {
                bodies: std::slice::from_ref(&body),
                camera: DVec3::ZERO,
                tc: 10.0,
                gate,
            };
            let mut admitted_somewhere = false;
            for i in 0..40 {
                let p = DVec3::new(0.1 * f64::from(i) - 2.0, 0.3, 0.05 * f64::from(i) - 1.0);
                let scan = (0..gate.count)
                    .find(|&k| snap.depth_in(&body, p, k) < gate.thickness)
                    .unwrap_or(gate.count);
                admitted_somewhere |= scan < gate.count && snap.depth_in(&body, p, scan) >= 0.0;
                for guess in [0, 1, 57, 200, 399, 1000] {
                    let (first, placed) = snap.first_slice(&body, p, guess);
                    assert_eq!(first, scan, "v {v}, point {i}");
                    // Where the point stands for that slice, as placed anew.
                    let want = (first < gate.count).then(|| {
                        let at = snap.placed(&body, p, first as f64);
                        (at, at.distance(snap.camera))
                    });
                    assert_eq!(placed, want, "v {v}, point {i}");
                }
            }
            assert!(
                admitted_somewhere,
                "v {v}: no point was admitted, the test tests nothing"
            );
        }
    }
}
