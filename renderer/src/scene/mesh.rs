//! Triangle meshes in an object's own coordinates (l.units, relative to the
//! object's reference point), a few primitives, and a Wavefront OBJ reader.

use crate::math;
use glam::DVec3;
use rayon::prelude::*;
use std::fmt;

/// An indexed triangle mesh. Faces are two-sided for shading; winding only
/// sets the direction of the stored normal.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, l.units.
    pub vertices: Vec<DVec3>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
    /// The material of each triangle, by index among its object's
    /// materials (0: the object's `material`, k: `face_materials[k - 1]`);
    /// empty when every triangle is of material 0.
    pub materials: Vec<u32>,
}

/// Why a mesh cannot be extruded.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshError {
    /// No triangles.
    Empty,
    /// A vertex with a non-finite coordinate.
    NonFiniteVertex {
        /// Its index.
        vertex: usize,
    },
    /// A triangle naming a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The vertex index it gives.
        index: u32,
    },
    /// Per-triangle material indices that do not match the triangles.
    MaterialCount {
        /// How many indices.
        materials: usize,
        /// How many triangles.
        triangles: usize,
    },
    /// A triangle with no area.
    DegenerateTriangle {
        /// The triangle.
        triangle: usize,
        /// Its area.
        area: f64,
    },
    /// A line of an OBJ file that cannot be read.
    Obj {
        /// Line number, from 1.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Empty => write!(f, "the mesh has no triangles"),
            MeshError::NonFiniteVertex { vertex } => {
                write!(f, "vertex {vertex} has a non-finite coordinate")
            }
            MeshError::IndexOutOfRange { triangle, index } => {
                write!(f, "triangle {triangle} refers to vertex {index}, which does not exist")
            }
            MeshError::DegenerateTriangle { triangle, area } => write!(
                f,
                "triangle {triangle} is degenerate (area {area:e}): its vertices are collinear or coincide"
            ),
            MeshError::Obj { line, message } => write!(f, "OBJ line {line}: {message}"),
            MeshError::MaterialCount {
                materials,
                triangles,
            } => write!(
                f,
                "{materials} per-triangle material indices for {triangles} triangles"
            ),
        }
    }
}

impl std::error::Error for MeshError {}

impl Mesh {
    /// A triangle's corners.
    pub fn corners(&self, triangle: usize) -> [DVec3; 3] {
        self.triangles[triangle].map(|i| self.vertices[i as usize])
    }

    /// The material index of triangle `triangle` (see [`Mesh::materials`]).
    pub fn material(&self, triangle: usize) -> u32 {
        self.materials.get(triangle).copied().unwrap_or(0)
    }

    /// Appends `other`, shifted by `offset`; triangles keep their material
    /// indices.
    pub fn append(&mut self, other: &Mesh, offset: DVec3) {
        if !(self.materials.is_empty() && other.materials.is_empty()) {
            let (mine, theirs) = (self.triangles.len(), other.triangles.len());
            self.materials.resize(mine, 0);
            self.materials
                .extend((0..theirs).map(|t| other.material(t)));
        }
        let base = self.vertices.len() as u32;
        self.vertices
            .extend(other.vertices.iter().map(|v| *v + offset));
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
    }

    /// The same triangles with every vertex mapped by `f`.
    pub fn map_vertices(&self, f: impl Fn(DVec3) -> DVec3) -> Mesh {
        Mesh {
            vertices: self.vertices.iter().map(|v| f(*v)).collect(),
            triangles: self.triangles.clone(),
            materials: self.materials.clone(),
        }
    }

    /// Rejects empty meshes, non-finite vertices, bad indices and triangles
    /// whose area is below 1e-12 of their longest edge squared.
    pub fn validate(&self) -> Result<(), MeshError> {
        if self.triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if !self.materials.is_empty() && self.materials.len() != self.triangles.len() {
            return Err(MeshError::MaterialCount {
                materials: self.materials.len(),
                triangles: self.triangles.len(),
            });
        }
        // A large mesh on both threads; the error is the first in order,
        // as on one. (Handing a small one to the thread pool would cost
        // more than checking it.)
        let parallel = self.triangles.len() >= PARALLEL_FROM;
        let bad = |v: &DVec3| !v.is_finite();
        let vertex = if parallel {
            self.vertices.par_iter().position_first(bad)
        } else {
            self.vertices.iter().position(bad)
        };
        if let Some(vertex) = vertex {
            return Err(MeshError::NonFiniteVertex { vertex });
        }
        let fault = |triangle: usize| self.triangle_fault(triangle);
        let first = if parallel {
            (0..self.triangles.len())
                .into_par_iter()
                .find_map_first(fault)
        } else {
            (0..self.triangles.len()).find_map(fault)
        };
        first.map_or(Ok(()), Err)
    }

    /// What is wrong with triangle `triangle`, if anything: a corner index
    /// out of range, or no area.
    fn triangle_fault(&self, triangle: usize) -> Option<MeshError> {
        let tri = &self.triangles[triangle];
        if let Some(&index) = tri.iter().find(|&&i| i as usize >= self.vertices.len()) {
            return Some(MeshError::IndexOutOfRange { triangle, index });
        }
        let [a, b, c] = self.corners(triangle);
        let area = 0.5 * (b - a).cross(c - a).length();
        let longest = (b - a)
            .length_squared()
            .max((c - b).length_squared())
            .max((a - c).length_squared());
        (area.is_nan() || area <= 1e-12 * longest)
            .then_some(MeshError::DegenerateTriangle { triangle, area })
    }

    /// A planar quadrilateral `corner, corner+u, corner+u+v, corner+v` (two triangles).
    pub fn quad(corner: DVec3, u: DVec3, v: DVec3) -> Mesh {
        Mesh {
            vertices: vec![corner, corner + u, corner + u + v, corner + v],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            materials: Vec::new(),
        }
    }

    /// An axis-aligned box with outward-wound faces, sharing its 8 corners.
    pub fn cuboid(min: DVec3, max: DVec3) -> Mesh {
        let v = |i: u32| {
            DVec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        };
        let faces: [[u32; 4]; 6] = [
            [0, 4, 6, 2], // x = min
            [1, 3, 7, 5], // x = max
            [0, 1, 5, 4], // y = min
            [2, 6, 7, 3], // y = max
            [0, 2, 3, 1], // z = min
            [4, 5, 7, 6], // z = max
        ];
        Mesh {
            vertices: (0..8).map(v).collect(),
            triangles: faces
                .iter()
                .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
                .collect(),
            materials: Vec::new(),
        }
    }

    /// A sphere of `radius` about the origin: `segments` around the axis
    /// (y) and `segments / 2` from pole to pole, poles fanned.
    pub fn uv_sphere(radius: f64, segments: u32) -> Mesh {
        let (nu, nv) = (segments.max(3), (segments / 2).max(2));
        let mut m = Mesh::default();
        let at = |i: u32, j: u32| {
            let (phi, theta) = (
                std::f64::consts::TAU * f64::from(i) / f64::from(nu),
                std::f64::consts::PI * f64::from(j) / f64::from(nv),
            );
            DVec3::new(
                math::sin(theta) * math::cos(phi),
                math::cos(theta),
                math::sin(theta) * math::sin(phi),
            ) * radius
        };
        for j in 0..nv {
            for i in 0..nu {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                let k = m.vertices.len() as u32;
                if j == 0 {
                    m.vertices.extend([a, c, d]);
                    m.triangles.push([k, k + 1, k + 2]);
                } else if j == nv - 1 {
                    m.vertices.extend([a, b, c]);
                    m.triangles.push([k, k + 1, k + 2]);
                } else {
                    m.vertices.extend([a, b, c, d]);
                    m.triangles.extend([[k, k + 1, k + 2], [k, k + 2, k + 3]]);
                }
            }
        }
        m
    }

    /// Reads the vertices (`v`) and faces (`f`, polygons fanned into
    /// triangles; `i`, `i/t`, `i//n`, `i/t/n` and negative indices) of a
    /// Wavefront OBJ file. Other statements are ignored.
    pub fn from_obj(text: &str) -> Result<Mesh, MeshError> {
        Mesh::read_obj(text.as_bytes())
    }

    /// [`Mesh::from_obj`] from `reader`, a block of a few MiB at a time,
    /// never holding the whole file (an OBJ of millions of triangles is
    /// read in little more than the memory of its mesh), each block parsed
    /// on all threads. A leading byte-order mark is skipped; a line that
    /// is not UTF-8, or a read that fails, is an error at its line.
    pub fn read_obj(reader: impl std::io::BufRead) -> Result<Mesh, MeshError> {
        super::obj::read(reader, super::obj::Cuts::file())
    }
}

/// Meshes of at least this many triangles are validated on both threads.
const PARALLEL_FROM: usize = 1 << 14;

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn cuboid_is_closed_and_outward() {
        let m = Mesh::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0));
        m.validate().unwrap();
        // Divergence theorem: sum of (centroid . area-normal) / 3 is the volume.
        let vol: f64 = (0..m.triangles.len())
            .map(|i| {
                let [a, b, c] = m.corners(i);
                a.dot(b.cross(c)) / 6.0
            })
            .sum();
        assert_abs_diff_eq!(vol, 8.0, epsilon = 1e-12);
    }

    #[test]
    fn degenerate_triangle_is_rejected() {
        let m = Mesh {
            vertices: vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0],
            triangles: vec![[0, 1, 2]],
            materials: Vec::new(),
        };
        assert!(matches!(
            m.validate(),
            Err(MeshError::DegenerateTriangle { triangle: 0, .. })
        ));
    }

    /// Validation runs on both threads (for a mesh this large), yet names
    /// the first fault in order (of each kind, vertices before triangles),
    /// as a pass on one would.
    #[test]
    fn the_first_fault_is_named_whatever_the_threads() {
        let n = 200_000;
        let mut m = Mesh {
            vertices: (0..n + 2)
                .map(|i| DVec3::new(i as f64, (i % 2) as f64, 0.0))
                .collect(),
            triangles: (0..n as u32).map(|i| [i, i + 1, i + 2]).collect(),
            materials: Vec::new(),
        };
        assert_eq!(m.validate(), Ok(()));
        for t in [150_000, 7, 90_001] {
            m.triangles[t] = [t as u32, t as u32, t as u32 + 1];
        }
        m.triangles[120_000][2] = n as u32 + 5;
        let first = |m: &Mesh| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(2)
                .build()
                .unwrap()
                .install(|| m.validate())
        };
        assert!(matches!(
            first(&m),
            Err(MeshError::DegenerateTriangle { triangle: 7, .. })
        ));
        m.triangles[7] = [7, 8, 9];
        assert!(matches!(
            first(&m),
            Err(MeshError::DegenerateTriangle {
                triangle: 90_001,
                ..
            })
        ));
        m.triangles[90_001] = [90_001, 90_002, 90_003];
        assert_eq!(
            first(&m),
            Err(MeshError::IndexOutOfRange {
                triangle: 120_000,
                index: n as u32 + 5
            })
        );
        m.vertices[160_000].y = f64::NAN;
        m.vertices[3].z = f64::INFINITY;
        assert_eq!(first(&m), Err(MeshError::NonFiniteVertex { vertex: 3 }));
    }

    #[test]
    fn obj_faces_are_fanned_and_checked() {
        let m =
            Mesh::from_obj("# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2/2/2 3//3 -1\n")
                .unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(matches!(
            Mesh::from_obj("v 0 0 0\nf 1 2 3\n"),
            Err(MeshError::Obj { line: 2, .. })
        ));
        assert!(matches!(
            Mesh::from_obj("v 0 zero 0\n"),
            Err(MeshError::Obj { line: 1, .. })
        ));
    }

    /// Read in small buffers, the mesh is the one the whole text gives; a
    /// byte-order mark is skipped; a line that is not UTF-8 and a failing
    /// read are errors at their line.
    #[test]
    fn obj_is_read_a_line_at_a_time() {
        let mut text = String::from("\u{feff}# grid\n");
        for i in 0..50 {
            text += &format!("v {i} {} 0.5\nv {i} {} 1.5\n", i * i, i + 1);
        }
        for i in 1..99 {
            text += &format!("f {i} {} {}\n", i + 1, i + 2);
        }
        let read = Mesh::read_obj(std::io::BufReader::with_capacity(7, text.as_bytes())).unwrap();
        let whole = Mesh::from_obj(text.strip_prefix('\u{feff}').unwrap()).unwrap();
        assert_eq!(read.vertices, whole.vertices);
        assert_eq!(read.triangles, whole.triangles);
        assert_eq!((read.vertices.len(), read.triangles.len()), (100, 98));

        let bad = b"v 0 0 0\nv 1 0 0\nv 0 \xff 0\n";
        assert!(matches!(
            Mesh::read_obj(&bad[..]),
            Err(MeshError::Obj { line: 3, ref message }) if message.contains("UTF-8")
        ));

        struct Failing(usize);
        impl std::io::Read for Failing {
            fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
                if self.0 == 0 {
                    return Err(std::io::Error::other("disk gone"));
                }
                self.0 -= 1;
                buf[..8].copy_from_slice(b"v 0 0 0\n");
                Ok(8)
            }
        }
        let e = Mesh::read_obj(std::io::BufReader::with_capacity(8, Failing(2))).unwrap_err();
        assert!(
            matches!(e, MeshError::Obj { line: 3, ref message } if message.contains("disk gone")),
            "{e}"
        );
    }
}
