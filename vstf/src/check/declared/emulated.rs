//! The 4D tracer's image of a view against the slice-by-slice emulator
//! ([`crate::emulator`], Hornof et al. 2025): a second oracle for whole
//! images, pixel by pixel.
//!
//! Both images show the kept objects in flat colours, one per object (the
//! tracer's through a copy of the fixture whose materials are ambient-lit
//! palette colours), so that a pixel names the object it sees.
//!
//! The emulator moves the object once per slice, to where it was when the
//! middle of the slice's light left it; a point's light may leave up to
//! half a slice's light time from that middle, so the emulator's object is
//! off by up to beta dz / 2, and where a line of sight grazes a surface the
//! hit may fall just outside both neighbouring gates: a sample may see
//! another object than the light cone's within beta dz of an edge. In
//! pixels, that blur is b = beta_max dz / (rho_min alpha) (rho_min the least
//! distance of the objects, alpha a pixel's angle at the image centre),
//! rounded up, plus the pixel itself. Tolerances:
//! - `disagreeing`: the fraction of the tracer's pixels within b pixels of a
//!   change of object;
//! - `off_band`: none, exactly (a disagreement farther from every edge is a
//!   failure of one oracle or the other);
//! - `edge_shift`: the mean over rows of the emulator's minus the tracer's
//!   leftmost edge (area method, n x n samples), against 0, within
//!   beta_max dz / (2 rho_min alpha) plus 3 standard errors of the mean and
//!   the area method's resolution 1/(n sqrt 12).

use crate::check::row::{Reading, Unit};
use crate::emulator::{Body, Form, Gate, Snapshot};
use crate::fixture::checks::{view_size, EmulatorRead, EmulatorSpec, ViewSpec};
use crate::fixture::Fixture;
use crate::measure::{self, Scan};
use crate::observer::{is_background, motion_of, Observer};
use crate::oracle::{contract, retarded};
use glam::DVec3;
use image::{Rgb, RgbImage};
use renderer::{Material, Shape};

/// A row's reading, its expectation and unit.
type Found = (Reading, f64, Unit);

/// The flat colour of the k-th kept object (distinct in every channel
/// combination, none near black).
fn palette(k: usize) -> DVec3 {
    const COLOURS: [[f64; 3]; 6] = [
        [0.9, 0.2, 0.2],
        [0.2, 0.9, 0.2],
        [0.2, 0.3, 0.9],
        [0.9, 0.9, 0.2],
        [0.9, 0.2, 0.9],
        [0.2, 0.9, 0.9],
    ];
    let c = COLOURS[k % COLOURS.len()];
    DVec3::from_array(c) * (1.0 - 0.1 * (k / COLOURS.len()) as f64)
}

/// The fixture with only `keep`, each in its flat palette colour under a
/// white ambient light, on black, without colour effects.
fn flat(f: &Fixture, keep: &[&str]) -> Result<Fixture, String> {
    let mut flat = f.only(keep).map_err(|e| e.to_string())?;
    for o in &mut flat.scene.objects {
        let k = keep.iter().position(|n| *n == o.name).unwrap_or(0);
        o.material = Material {
            diffuse: 0.0,
            ..Material::matte(palette(k))
        };
    }
    let light = &mut flat.scene.light;
    (light.color, light.ambient, light.spectrum) = (DVec3::ZERO, 1.0, None);
    flat.scene.background = DVec3::ZERO;
    (flat.spec.image.doppler, flat.spec.image.searchlight) = (false, false);
    Ok(flat)
}

/// The kept objects as the emulator's bodies, contracted as the model has it.
fn bodies(setup: &Observer, keep: &[&str]) -> Result<Vec<Body>, String> {
    keep.iter()
        .map(|name| {
            let m = motion_of(setup.fixture, name, setup.model)?;
            let shape_of = |p: DVec3| {
                if m.contracted {
                    contract(p, m.velocity)
                } else {
                    p
                }
            };
            let form = match &setup.fixture.object(name)?.shape {
                Shape::Mesh(mesh) => Form::Triangles(
                    (0..mesh.triangles.len())
                        .map(|t| mesh.corners(t).map(shape_of))
                        .collect(),
                ),
                Shape::Sphere { radius } => {
                    Body::sphere(*radius, 0.0, DVec3::ZERO, m.velocity, m.contracted).form
                }
            };
            Ok(Body {
                form,
                t0: m.start.t,
                x0: m.start.x,
                velocity: m.velocity,
            })
        })
        .collect()
}

/// The gate: `slices` slices over the distances at which the bodies can be
/// seen, from where each reference point is seen, two reaches either side.
fn gate(setup: &Observer, bodies: &[Body], slices: usize) -> Result<(Gate, f64), String> {
    let camera = setup.camera_x();
    let (mut near, mut far, mut closest) = (f64::INFINITY, 0.0f64, f64::INFINITY);
    for b in bodies {
        let p = crate::oracle::PointWorldline {
            t0: b.t0,
            x0: b.x0,
            v: b.velocity,
        };
        let seen =
            retarded(&p, setup.camera_t, camera).ok_or("a body is never seen from the camera")?;
        let (rho, r) = (seen.x.distance(camera), b.reach());
        near = near.min(rho - 2.0 * r);
        far = far.max(rho + 2.0 * r);
        closest = closest.min(rho - r);
    }
    let near = near.max(0.0);
    let gate = Gate {
        near,
        thickness: (far - near) / slices as f64,
        count: slices,
    };
    Ok((gate, closest.max(1e-9)))
}

/// The class of each tracer pixel: the nearest palette colour, or `None`
/// for the background.
fn tracer_classes(img: &RgbImage, n: usize) -> Vec<Option<usize>> {
    img.pixels()
        .map(|p| {
            let c = DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])) / 255.0;
            if is_background(c, DVec3::ZERO) {
                return None;
            }
            (0..n).min_by(|&a, &b| {
                (palette(a) - c)
                    .length_squared()
                    .total_cmp(&(palette(b) - c).length_squared())
            })
        })
        .collect()
}

/// The number of pixels within `b` (Chebyshev) of a pixel whose right or
/// lower neighbour shows another class: the blur band about the edges.
fn band(classes: &[Option<usize>], (w, h): (u32, u32), b: i64) -> Vec<bool> {
    let (w, h) = (i64::from(w), i64::from(h));
    let at = |x: i64, y: i64| classes[(y * w + x) as usize];
    let mut edge = vec![false; classes.len()];
    for y in 0..h {
        for x in 0..w {
            let differs =
                (x + 1 < w && at(x + 1, y) != at(x, y)) || (y + 1 < h && at(x, y + 1) != at(x, y));
            if differs {
                edge[(y * w + x) as usize] = true;
            }
        }
    }
    let mut near = vec![false; classes.len()];
    for y in 0..h {
        for x in 0..w {
            if !edge[(y * w + x) as usize] {
                continue;
            }
            for yy in (y - b - 1).max(0)..=(y + b + 1).min(h - 1) {
                for xx in (x - b - 1).max(0)..=(x + b + 1).min(w - 1) {
                    near[(yy * w + xx) as usize] = true;
                }
            }
        }
    }
    near
}

/// Measures the emulator check `e` in `view`; also where each kept
/// object's reference point is seen, to mark.
pub(super) fn measure(
    measuring: &Observer,
    described: &Observer,
    e: &EmulatorSpec,
    view: &ViewSpec,
) -> Result<(Found, Vec<DVec3>), String> {
    let keep: Vec<&str> = e.keep.iter().map(String::as_str).collect();
    let marks = bodies(described, &keep)?
        .iter()
        .filter_map(|b| {
            let p = crate::oracle::PointWorldline {
                t0: b.t0,
                x0: b.x0,
                v: b.velocity,
            };
            retarded(&p, described.camera_t, described.camera_x()).map(|r| r.direction)
        })
        .collect();
    Ok((compare(measuring, described, e, view)?, marks))
}

/// The comparison of the two images (see the module's documentation).
fn compare(
    measuring: &Observer,
    described: &Observer,
    e: &EmulatorSpec,
    view: &ViewSpec,
) -> Result<Found, String> {
    let keep: Vec<&str> = e.keep.iter().map(String::as_str).collect();
    let bodies = bodies(described, &keep)?;
    let (gate, closest) = gate(described, &bodies, e.slices)?;
    let size = view_size(&measuring.fixture.spec, view);
    let flat = flat(measuring.fixture, &keep)?;
    let tracer = Observer {
        fixture: &flat,
        ..*measuring
    };
    let camera = described.pinhole(size)?;
    let snapshot = Snapshot {
        bodies: &bodies,
        camera: described.camera_x(),
        tc: described.camera_t,
        gate,
    };
    let speed = bodies
        .iter()
        .map(|b| b.velocity.length())
        .fold(0.0, f64::max);
    let (cx, cy) = (f64::from(size.0) / 2.0, f64::from(size.1) / 2.0);
    let pixel = closest * camera.angular_footprint(cx, cy, true);
    let blur_px = speed * gate.thickness / pixel;
    match e.read {
        EmulatorRead::Disagreeing | EmulatorRead::OffBand => {
            if blur_px >= 1.0 {
                return Err(format!(
                    "{} slices blur the emulated image by {blur_px:.2} px: its slices tear apart by \
                     up to that much wherever a surface's distance crosses a slice boundary, not only \
                     at edges, so pixels are compared only for gates thinner than a pixel's blur \
                     (more slices); read edge_shift for thicker ones",
                    e.slices
                ));
            }
            let (img, _) = tracer.measuring_render(&keep, size, 1)?;
            let ours = tracer_classes(&img, keep.len());
            let theirs = snapshot.cells(&camera, size, 1, pixel / POINTS_PER_CELL);
            let near = band(&ours, size, blur_px.ceil() as i64);
            let differ: Vec<bool> = ours.iter().zip(&theirs).map(|(a, b)| a != b).collect();
            let total = ours.len() as f64;
            let count =
                |f: &dyn Fn(usize) -> bool| (0..ours.len()).filter(|&i| f(i)).count() as f64;
            Ok(if e.read == EmulatorRead::Disagreeing {
                let reading = Reading {
                    value: count(&|i| differ[i]) / total,
                    tolerance: count(&|i| near[i]) / total,
                };
                (reading, 0.0, Unit::Ratio)
            } else {
                let reading = Reading {
                    value: count(&|i| differ[i] && !near[i]),
                    tolerance: 0.0,
                };
                (reading, 0.0, Unit::Pixels)
            })
        }
        EmulatorRead::EdgeShift => {
            let n = e.samples.unwrap_or(2);
            let (img, _) = tracer.measuring_render(&keep, size, n * n)?;
            let cells = snapshot.cells(&camera, size, n, pixel / f64::from(n) / POINTS_PER_CELL);
            let emulated = composite(&cells, size, n);
            edge_shift(&img, &emulated, n, blur_px / 2.0)
        }
    }
}

/// Surface points per image cell's width at the objects' least distance:
/// enough that every cell a surface covers receives points, where the
/// image stretches the surface up to this much.
const POINTS_PER_CELL: f64 = 3.0;

/// The emulator's image: each pixel the mean of its n x n cells' palette colours.
fn composite(cells: &[Option<usize>], (w, h): (u32, u32), n: u32) -> RgbImage {
    RgbImage::from_fn(w, h, |x, y| {
        let mut sum = DVec3::ZERO;
        for j in 0..n {
            for i in 0..n {
                let cell = cells[((y * n + j) * w * n + x * n + i) as usize];
                sum += cell.map_or(DVec3::ZERO, palette);
            }
        }
        let c = sum / f64::from(n * n) * 255.0;
        Rgb(c.round().to_array().map(|v| v.clamp(0.0, 255.0) as u8))
    })
}

/// The mean shift of the leftmost edge (from the background) between the
/// emulated and the traced image, over the rows where both show one.
fn edge_shift(
    traced: &RgbImage,
    emulated: &RgbImage,
    n: u32,
    bound_px: f64,
) -> Result<Found, String> {
    let left = |img: &RgbImage, y: u32| {
        let scan = Scan {
            horizontal: true,
            at: y,
        };
        measure::edge(img, scan, 0, 1, |c| is_background(c, DVec3::ZERO))
    };
    let shifts: Vec<f64> = (0..traced.height())
        .filter_map(|y| Some(left(emulated, y)? - left(traced, y)?))
        .collect();
    if shifts.len() < 3 {
        return Err(format!(
            "the left edge is found on only {} rows of both images",
            shifts.len()
        ));
    }
    let m = shifts.len() as f64;
    let mean = shifts.iter().sum::<f64>() / m;
    let var = shifts.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / (m - 1.0);
    // The tracer's area method resolves 1/(n sqrt 12) pixel; the emulator
    // counts a cell covered when any point lands in it, which may put its
    // silhouette up to a cell (1/n pixel) outside the true one.
    let resolution = 1.0 / (f64::from(n) * 12f64.sqrt()) + 1.0 / f64::from(n);
    let reading = Reading {
        value: mean,
        tolerance: bound_px + 3.0 * (var / m).sqrt() + resolution,
    };
    Ok((reading, 0.0, Unit::Pixels))
}
