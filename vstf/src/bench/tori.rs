//! The side-by-side benchmark's scene: a 14 x 8 grid of tilted tori, as an
//! OBJ file and a fixture that renders it like Embree's side of the
//! benchmark (camera at (0, 0, 30) looking at the origin, vertical field of
//! view 40 degrees, one sample at each pixel, no shadows or reflections).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

const COLUMNS: usize = 14;
const ROWS: usize = 8;

/// The tori's vertices and triangles (indices from 0): about `total`
/// triangles in all.
pub fn grid(total: usize) -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
    let per = (total / (COLUMNS * ROWS)).max(8) as f64;
    let m = ((per / 4.0).sqrt().round() as usize).max(3); // minor segments
    let n = ((per / (2.0 * m as f64)).round() as usize).max(3); // major segments
    let (big, small, spacing) = (1.0, 0.4, 2.6);
    let mut verts = Vec::new();
    let mut faces = Vec::new();
    for k in 0..COLUMNS * ROWS {
        let (row, col) = (k / COLUMNS, k % COLUMNS);
        let cx = (col as f64 - (COLUMNS as f64 - 1.0) / 2.0) * spacing;
        let cy = (row as f64 - (ROWS as f64 - 1.0) / 2.0) * spacing;
        let (ax, ay) = (0.5 + 0.13 * k as f64, 0.3 + 0.07 * k as f64);
        let base = verts.len();
        for i in 0..n {
            let u = std::f64::consts::TAU * i as f64 / n as f64;
            for j in 0..m {
                let v = std::f64::consts::TAU * j as f64 / m as f64;
                let p = [
                    (big + small * v.cos()) * u.cos(),
                    (big + small * v.cos()) * u.sin(),
                    small * v.sin(),
                ];
                let [x, y, z] = tilted(p, ax, ay);
                verts.push([x + cx, y + cy, z]);
            }
        }
        for i in 0..n {
            for j in 0..m {
                let a = base + i * m + j;
                let b = base + ((i + 1) % n) * m + j;
                let c = base + ((i + 1) % n) * m + (j + 1) % m;
                let d = base + i * m + (j + 1) % m;
                faces.push([a, b, c]);
                faces.push([a, c, d]);
            }
        }
    }
    (verts, faces)
}

/// `p` turned by `ax` about x, then by `ay` about y.
fn tilted([x, y, z]: [f64; 3], ax: f64, ay: f64) -> [f64; 3] {
    let (y, z) = (y * ax.cos() - z * ax.sin(), y * ax.sin() + z * ax.cos());
    let (x, z) = (x * ay.cos() + z * ay.sin(), -x * ay.sin() + z * ay.cos());
    [x, y, z]
}

/// The OBJ file and fixture [`fn@write`] writes, for `total` triangles at
/// `w` x `h`.
/// How the tori move: at rest (the scene Embree's side traces), or as a
/// Lorentz-contracted V_obj at 0.9c along x seen under the relativistic
/// model, for the cost of motion against the static frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// At rest, seen with infinitely fast light.
    Static,
    /// A V_obj at 0.9c along x, seen on the camera's past light cone.
    Moving,
}

/// The OBJ file and the fixture of the `total`-triangle scene at `w` x `h`.
pub fn paths(dir: &Path, total: usize, (w, h): (u32, u32), motion: Motion) -> (PathBuf, PathBuf) {
    let moving = if motion == Motion::Moving {
        "-0.9c"
    } else {
        ""
    };
    (
        dir.join(format!("tori-{total}.obj")),
        dir.join(format!("tori-{total}{moving}-{w}x{h}.json")),
    )
}

/// Writes the scene (unless there already) into `dir`: its OBJ file and
/// fixture, and the number of triangles.
pub fn write(
    dir: &Path,
    total: usize,
    (w, h): (u32, u32),
    motion: Motion,
) -> Result<(PathBuf, PathBuf, usize), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let (obj, fixture) = paths(dir, total, (w, h), motion);
    let (verts, faces) = grid(total);
    if !obj.is_file() {
        let mut text = String::with_capacity(40 * (verts.len() + faces.len()));
        for v in &verts {
            let _ = writeln!(text, "v {:.7} {:.7} {:.7}", v[0], v[1], v[2]);
        }
        for f in &faces {
            let _ = writeln!(text, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
        }
        crate::output::write_atomic(&obj, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", obj.display()))?;
    }
    if !fixture.is_file() {
        let text = serde_json::to_string_pretty(&spec(total, faces.len(), (w, h), motion))
            .expect("a fixture serialises");
        crate::output::write_atomic(&fixture, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", fixture.display()))?;
    }
    Ok((obj, fixture, faces.len()))
}

/// The fixture. Moving, the tori's reference point crosses x = 0 at
/// t = -30, when light leaves the grid's plane to reach the camera at t = 0.
fn spec(total: usize, triangles: usize, (w, h): (u32, u32), motion: Motion) -> serde_json::Value {
    let mesh = serde_json::json!({"obj": {"path": format!("tori-{total}.obj")}});
    let color = serde_json::json!({"color": [0.8, 0.6, 0.4]});
    let (what, model, object) = match motion {
        Motion::Static => (
            "static (the Embree side-by-side benchmark)",
            "infinite",
            serde_json::json!({"name": "tori", "mesh": mesh, "position": [0, 0, 0], "material": color}),
        ),
        Motion::Moving => (
            "a V_obj moving at 0.9c along x, relativistic (the cost of motion)",
            "relativistic",
            serde_json::json!({"name": "tori", "kind": "V_obj", "mesh": mesh, "material": color,
                "worldline": {"start": [-130.0, -90.0, 0, 0], "extrusion": [200.0, 180.0, 0, 0]}}),
        ),
    };
    serde_json::json!({
        "description": format!("{triangles} triangles: a grid of tilted tori, {what}"),
        "model": model,
        "camera": {"position": [0, 0, 30], "t": 0, "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40},
        "light": {"position": [10, 20, 40], "color": [1, 1, 1], "ambient": 0.3},
        "background": [0, 0, 0],
        "image": {"width": w, "height": h, "spp": 1, "shutter": 0, "seed": 1, "max_depth": 0, "shadows": false},
        "objects": [object],
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_grid_has_about_the_triangles_asked_for_and_closed_tori() {
        for total in [10_000, 100_000] {
            let (verts, faces) = super::grid(total);
            let n = faces.len() as f64;
            assert!((n / total as f64 - 1.0).abs() < 0.1, "{n} for {total}");
            // A closed torus: every edge is shared by exactly two triangles.
            let mut edges = std::collections::HashMap::new();
            for f in &faces {
                for (a, b) in [(f[0], f[1]), (f[1], f[2]), (f[2], f[0])] {
                    *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
            assert!(edges.values().all(|&k| k == 2));
            assert!(faces.iter().flatten().all(|&i| i < verts.len()));
        }
    }
}
