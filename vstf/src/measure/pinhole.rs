//! The camera model of the measurements, written from the formulas rather
//! than borrowed from the ray tracer, so that an error in its
//! camera shows as a mismatch instead of cancelling out.
//!
//! A pinhole at a lab position with an orthonormal attitude (forward, right,
//! up) and a vertical field of view; pixel (0, 0) is the top left and pixel
//! centres lie at half-integers. The attitude and the image plane belong to
//! the camera's own rest frame. A camera moving through the lab sees along
//! lab lines of sight turned by its motion (paper 2.1 and 3.2): by the
//! Lorentz boost of the light's null 4-vector (relativistic aberration,
//! paper eq. 3-5 and 9), by Galilean addition of velocities (the classical
//! model), or not at all when light is instantaneous.

use glam::DVec3;

/// How the camera's motion turns its lines of sight into the lab's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kinematics {
    /// Instantaneous light: the camera's motion turns nothing.
    None,
    /// Galilean addition of the camera's velocity to the light's.
    Galilean,
    /// The Lorentz boost of the light's null 4-vector.
    Lorentz,
}

impl Kinematics {
    /// The kinematics of a model: none with infinite light speed, else
    /// Lorentz when the Lorentz transform is on and Galilean when it is off.
    pub fn of(finite_light: bool, lorentz: bool) -> Kinematics {
        match (finite_light, lorentz) {
            (false, _) => Kinematics::None,
            (true, false) => Kinematics::Galilean,
            (true, true) => Kinematics::Lorentz,
        }
    }
}

/// A plane in the lab: points p with normal.(p - point) = 0.
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    /// A point on the plane.
    pub point: DVec3,
    /// The plane's normal.
    pub normal: DVec3,
}

impl Plane {
    /// The plane of constant x.
    pub fn x(x: f64) -> Plane {
        Plane {
            point: DVec3::new(x, 0.0, 0.0),
            normal: DVec3::X,
        }
    }
    /// The plane of constant y.
    pub fn y(y: f64) -> Plane {
        Plane {
            point: DVec3::new(0.0, y, 0.0),
            normal: DVec3::Y,
        }
    }
    /// The plane of constant z.
    pub fn z(z: f64) -> Plane {
        Plane {
            point: DVec3::new(0.0, 0.0, z),
            normal: DVec3::Z,
        }
    }
}

/// A pinhole camera at lab `position` (at the camera event), moving with
/// lab `velocity` (fraction of c).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pinhole {
    /// Lab position at the camera event.
    pub position: DVec3,
    /// Unit line of sight through the image centre, in the camera's frame.
    pub forward: DVec3,
    /// Unit vector along the image's rows, to the right.
    pub right: DVec3,
    /// Unit vector along the image's columns, upwards.
    pub up: DVec3,
    /// tan(vfov / 2) of the vertical field of view: the image plane's
    /// half-height at unit distance (found once: a measurement projects
    /// millions of points).
    tan_half_v: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Lab velocity (fraction of c).
    pub velocity: DVec3,
    /// How the velocity turns lines of sight.
    pub kinematics: Kinematics,
}

impl Pinhole {
    /// A camera at rest looking from `position` towards the point `look_at`,
    /// the image's up as near `up` as the view allows; `None` when
    /// `look_at` is the position or `up` is along the view.
    pub fn looking_at(
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        vfov_deg: f64,
        (width, height): (u32, u32),
    ) -> Option<Pinhole> {
        Pinhole::facing(
            position,
            (look_at - position).try_normalize()?,
            up,
            vfov_deg,
            (width, height),
        )
    }

    /// A camera at rest turned by yaw (right-handed about +y, 0 looking
    /// along -z, 90 along -x) and pitch (above the horizontal), degrees;
    /// the image's up follows +y.
    pub fn yaw_pitch(
        position: DVec3,
        (yaw_deg, pitch_deg): (f64, f64),
        vfov_deg: f64,
        (width, height): (u32, u32),
    ) -> Option<Pinhole> {
        let (yaw, pitch) = (yaw_deg.to_radians(), pitch_deg.to_radians());
        let forward = DVec3::new(
            -yaw.sin() * pitch.cos(),
            pitch.sin(),
            -yaw.cos() * pitch.cos(),
        );
        Pinhole::facing(position, forward, DVec3::Y, vfov_deg, (width, height))
    }

    /// The right-handed orthonormal attitude of a unit `forward`: right =
    /// forward x up, up = right x forward.
    fn facing(
        position: DVec3,
        forward: DVec3,
        up_hint: DVec3,
        vfov_deg: f64,
        (width, height): (u32, u32),
    ) -> Option<Pinhole> {
        let right = forward.cross(up_hint).try_normalize()?;
        Some(Pinhole {
            position,
            forward,
            right,
            up: right.cross(forward),
            tan_half_v: (vfov_deg.to_radians() / 2.0).tan(),
            width,
            height,
            velocity: DVec3::ZERO,
            kinematics: Kinematics::None,
        })
    }

    /// The same camera moving with lab `velocity`; `None` at or above light speed.
    pub fn moving(self, velocity: DVec3, kinematics: Kinematics) -> Option<Pinhole> {
        (velocity.is_finite() && velocity.length_squared() < 1.0).then_some(Pinhole {
            velocity,
            kinematics,
            ..self
        })
    }

    /// The camera with its motion removed: its lab lines of sight are then
    /// those of its own frame.
    pub fn still(self) -> Pinhole {
        Pinhole {
            velocity: DVec3::ZERO,
            kinematics: Kinematics::None,
            ..self
        }
    }

    /// tan(vfov / 2): the image plane's half-height at unit distance.
    fn tan_half_v(&self) -> f64 {
        self.tan_half_v
    }

    fn aspect(&self) -> f64 {
        f64::from(self.width) / f64::from(self.height)
    }

    /// The unit line of sight, in the camera's own frame, through the
    /// continuous pixel position (px, py): the image plane at unit distance
    /// spans [-tan(vfov/2) aspect, +] across and [-tan(vfov/2), +] up.
    pub fn rest_direction(&self, px: f64, py: f64) -> DVec3 {
        let th = self.tan_half_v();
        let u = (2.0 * px / f64::from(self.width) - 1.0) * th * self.aspect();
        let v = (1.0 - 2.0 * py / f64::from(self.height)) * th;
        (self.forward + self.right * u + self.up * v).normalize()
    }

    /// The unit lab line of sight (from the camera into the scene) through
    /// the continuous pixel position (px, py).
    pub fn direction(&self, px: f64, py: f64) -> DVec3 {
        self.to_lab(self.rest_direction(px, py))
    }

    /// A line of sight `n` of the camera's frame as seen in the lab.
    ///
    /// Lorentz: light arriving along `n` has the past-directed null
    /// 4-vector (-1, n) in the camera's frame; the boost by the camera's
    /// velocity v gives t = gamma (-1 + v.n), x = n + ((gamma - 1) v.n / v^2
    /// - gamma) v, and the lab line of sight is x / -t. Galilean: light at c
    ///   in the lab along -d moves along -(d + v) relative to the camera, so
    ///   d + v = lambda n with |d| = 1, lambda = n.v + sqrt((n.v)^2 - v^2 + 1).
    pub fn to_lab(&self, n: DVec3) -> DVec3 {
        let v = self.velocity;
        match self.kinematics {
            _ if v == DVec3::ZERO => n,
            Kinematics::None => n,
            Kinematics::Lorentz => {
                let (t, x) = boost(-1.0, n, v);
                (x / -t).normalize()
            }
            Kinematics::Galilean => {
                let nv = n.dot(v);
                let lambda = nv + (nv * nv - v.length_squared() + 1.0).sqrt();
                (n * lambda - v).normalize()
            }
        }
    }

    /// A lab line of sight `d` in the camera's frame: the inverse of
    /// [`Pinhole::to_lab`] (the boost by -v; Galilean: d + v).
    pub fn from_lab(&self, d: DVec3) -> DVec3 {
        let v = self.velocity;
        match self.kinematics {
            _ if v == DVec3::ZERO => d,
            Kinematics::None => d,
            Kinematics::Lorentz => {
                let (t, x) = boost(-1.0, d, -v);
                (x / -t).normalize()
            }
            Kinematics::Galilean => (d + v).normalize(),
        }
    }

    /// The continuous pixel position where light arriving along lab line of
    /// sight `d` lands; `None` when it is behind the camera.
    pub fn pixel_of(&self, d: DVec3) -> Option<(f64, f64)> {
        self.pixel_of_rest(self.from_lab(d))
    }

    /// The continuous pixel position of a line of sight `n` of the camera's
    /// own frame: its central projection onto the image plane.
    pub fn pixel_of_rest(&self, n: DVec3) -> Option<(f64, f64)> {
        let f = n.dot(self.forward);
        if f <= 0.0 {
            return None;
        }
        let th = self.tan_half_v();
        let u = n.dot(self.right) / f / (th * self.aspect());
        let v = n.dot(self.up) / f / th;
        Some((
            (u + 1.0) * f64::from(self.width) / 2.0,
            (1.0 - v) * f64::from(self.height) / 2.0,
        ))
    }

    /// Where the lab line of sight through continuous pixel (px, py) meets
    /// `plane`: the spatial position of the seen event, if the seen point
    /// lies on it.
    pub fn on_plane(&self, px: f64, py: f64, plane: Plane) -> Option<DVec3> {
        let d = self.direction(px, py);
        let denom = plane.normal.dot(d);
        if denom.abs() < 1e-12 {
            return None;
        }
        let s = plane.normal.dot(plane.point - self.position) / denom;
        (s > 0.0).then(|| self.position + d * s)
    }

    /// Size on `plane` of one pixel step along a row (`horizontal`) or a
    /// column at (px, py): the footprint that turns an edge uncertainty in
    /// pixels into l.units.
    pub fn footprint(&self, px: f64, py: f64, horizontal: bool, plane: Plane) -> Option<f64> {
        let (qx, qy) = step(px, py, horizontal);
        Some((self.on_plane(qx, qy, plane)? - self.on_plane(px, py, plane)?).length())
    }

    /// Angle (radians) between the lab lines of sight of two neighbouring
    /// pixels at (px, py), along a row (`horizontal`) or a column.
    pub fn angular_footprint(&self, px: f64, py: f64, horizontal: bool) -> f64 {
        let (qx, qy) = step(px, py, horizontal);
        self.direction(px, py).angle_between(self.direction(qx, qy))
    }
}

/// One pixel further along a row or a column.
fn step(px: f64, py: f64, horizontal: bool) -> (f64, f64) {
    if horizontal {
        (px + 1.0, py)
    } else {
        (px, py + 1.0)
    }
}

/// The 4-vector (t, x) of a frame moving with lab velocity `v` (|v| < 1),
/// in the lab: t_lab = gamma (t + v.x), x_lab = x + ((gamma - 1) v.x / v^2
/// + gamma t) v, gamma = 1 / sqrt(1 - v^2) (paper eq. 2 and 3-5).
fn boost(t: f64, x: DVec3, v: DVec3) -> (f64, DVec3) {
    let v2 = v.length_squared();
    let gamma = 1.0 / (1.0 - v2).sqrt();
    let vx = v.dot(x);
    (
        gamma * (t + vx),
        x + v * ((gamma - 1.0) * vx / v2 + gamma * t),
    )
}

/// Azimuth of a lab direction (about +y, from -z towards +x), degrees.
pub fn azimuth(v: &DVec3) -> f64 {
    v.x.atan2(-v.z).to_degrees()
}

/// Elevation of a lab direction above the x-z plane, degrees.
pub fn elevation(v: &DVec3) -> f64 {
    v.y.atan2(v.x.hypot(v.z)).to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    fn camera() -> Pinhole {
        Pinhole::looking_at(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::ZERO,
            DVec3::Y,
            60.0,
            (64, 48),
        )
        .unwrap()
    }

    #[test]
    fn pixel_of_inverts_direction_for_every_kinematics() {
        for k in [Kinematics::None, Kinematics::Galilean, Kinematics::Lorentz] {
            let c = camera().moving(DVec3::new(0.3, -0.2, 0.5), k).unwrap();
            for (px, py) in [(0.5, 0.5), (32.0, 24.0), (63.2, 10.7)] {
                let (x, y) = c.pixel_of(c.direction(px, py)).unwrap();
                assert!((x - px).abs() < 1e-9 && (y - py).abs() < 1e-9, "{k:?}");
            }
        }
        assert!(camera().pixel_of(-camera().forward).is_none());
    }

    #[test]
    fn lorentz_lines_of_sight_follow_the_half_angle_formula() {
        // Eq. (9) for the observer: tan(a'/2) = sqrt((1 - b)/(1 + b)) tan(a/2),
        // angles from the observer's velocity; a' in its frame, a in the lab.
        let b = 0.6;
        let c = camera()
            .moving(camera().forward * b, Kinematics::Lorentz)
            .unwrap();
        for (px, py) in [(3.0, 24.0), (40.0, 2.0)] {
            let rest = c.rest_direction(px, py).angle_between(c.forward);
            let lab = c.direction(px, py).angle_between(c.forward);
            let want = ((1.0 - b) / (1.0 + b)).sqrt() * (lab / 2.0).tan();
            assert_abs_diff_eq!((rest / 2.0).tan(), want, epsilon = 1e-12);
        }
    }

    #[test]
    fn a_plane_is_met_where_the_line_of_sight_says() {
        let c = camera();
        let p = c.on_plane(20.0, 30.0, Plane::y(0.0)).unwrap();
        assert_abs_diff_eq!(p.y, 0.0, epsilon = 1e-12);
        assert_abs_diff_eq!(
            ((p - c.position).normalize() - c.direction(20.0, 30.0)).length(),
            0.0,
            epsilon = 1e-12
        );
        // A plane behind the camera (it looks towards -z from z = 3) is never met.
        assert!(c.on_plane(32.0, 24.0, Plane::z(10.0)).is_none());
    }
}
