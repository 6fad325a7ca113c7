//! The fixture file format: a JSON scene (objects, camera, light, model,
//! image settings), read with the JSON path of any bad field in the error.
//! The format is documented with an example in `docs/fixtures.md`.

use glam::DVec3;
use renderer::{
    Attitude, Camera, Event, FourVector, Hyperbolic, Keyframe, Light, Material, Mesh, Model,
    Motion, ObjectKind, RenderSettings, Scene, SceneError, SceneObject, Shape, SpectrumField,
};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::{Path, PathBuf};

/// A fixture that cannot be used: the file, the JSON path of the field, and what was expected.
#[derive(Debug, Clone, PartialEq)]
pub struct FixtureError {
    pub file: PathBuf,
    pub path: String,
    pub message: String,
}

impl fmt::Display for FixtureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() || self.path == "." {
            write!(f, "{}: {}", self.file.display(), self.message)
        } else {
            write!(
                f,
                "{}: {}: {}",
                self.file.display(),
                self.path,
                self.message
            )
        }
    }
}

impl std::error::Error for FixtureError {}

/// Largest image accepted, in pixels (8192 x 8192).
pub const MAX_PIXELS: u64 = 8192 * 8192;
/// Largest side accepted, in pixels.
pub const MAX_SIDE: u32 = 16384;
/// Most samples per pixel accepted.
pub const MAX_SPP: u32 = 4096;

fn default_up() -> DVec3 {
    DVec3::Y
}
fn default_vfov() -> f64 {
    50.0
}
fn default_static_lifetime() -> [f64; 2] {
    [-1.0e6, 1.0e6]
}
fn default_background() -> DVec3 {
    DVec3::new(0.02, 0.02, 0.05)
}

/// The camera (paper 3.2): at rest in the lab at (t, position).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    /// Lab position, l.units.
    pub position: DVec3,
    /// Lab time of the camera event, t.units.
    pub t: f64,
    /// Point looked at (use either this or yaw_deg/pitch_deg).
    #[serde(default)]
    pub look_at: Option<DVec3>,
    #[serde(default = "default_up")]
    pub up: DVec3,
    #[serde(default)]
    pub yaw_deg: Option<f64>,
    #[serde(default)]
    pub pitch_deg: Option<f64>,
    /// Vertical field of view, degrees.
    #[serde(default = "default_vfov")]
    pub vfov_deg: f64,
    /// Lab velocity of the camera (fraction of c); `position` is where it
    /// is at time `t`. At rest by default, as in the paper.
    #[serde(default)]
    pub velocity: Option<DVec3>,
}

/// Image settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageSpec {
    pub width: u32,
    pub height: u32,
    #[serde(default = "one")]
    pub spp: u32,
    /// Shutter interval of camera time for motion blur, t.units.
    #[serde(default)]
    pub shutter: f64,
    #[serde(default = "one_u64")]
    pub seed: u64,
    #[serde(default = "four")]
    pub max_depth: u32,
    /// Trace shadow rays (default true).
    #[serde(default = "yes")]
    pub shadows: bool,
    /// Doppler-shift wavelengths (spectral rendering; default false).
    #[serde(default)]
    pub doppler: bool,
    /// Scale intensities by the searchlight effect (default false).
    #[serde(default)]
    pub searchlight: bool,
}

fn one() -> u32 {
    1
}
fn one_u64() -> u64 {
    1
}
fn yes() -> bool {
    true
}
fn four() -> u32 {
    4
}

/// A mesh primitive, in the object's own coordinates.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum MeshSpec {
    /// corner, corner+u, corner+u+v, corner+v.
    Quad { corner: DVec3, u: DVec3, v: DVec3 },
    /// Axis-aligned box.
    Cuboid { min: DVec3, max: DVec3 },
    /// The paper's right-angle flange (two two-sided planes).
    Flange { height: f64, width: f64, depth: f64 },
    /// Bars of square section on the plane y (see [`bar_grid`]).
    BarGrid {
        count: u32,
        spacing: f64,
        first: f64,
        thickness: f64,
        y: f64,
    },
    /// A Wavefront OBJ file, relative to the fixture file.
    Obj { path: PathBuf },
    /// Explicit triangles.
    Triangles {
        vertices: Vec<DVec3>,
        indices: Vec<[u32; 3]>,
    },
    /// Several meshes merged.
    Group(Vec<MeshSpec>),
    /// A sphere tessellated into `segments` around and `segments / 2` from pole to pole.
    Sphere { radius: f64, segments: u32 },
    /// An exact sphere (not tessellated), centred on the reference point.
    AnalyticSphere { radius: f64 },
}

/// An object's worldline: from `start`, either `extrusion`, or `velocity`
/// with `proper_lifetime`, or `hyperbolic`; or else `keyframes` alone.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldlineSpec {
    /// Event (t, x, y, z) where the reference point starts.
    #[serde(default)]
    pub start: Option<[f64; 4]>,
    /// Lab 4-vector (dt, dx, dy, dz) of the temporal extrusion.
    #[serde(default)]
    pub extrusion: Option<[f64; 4]>,
    /// Lab velocity (fraction of c).
    #[serde(default)]
    pub velocity: Option<DVec3>,
    /// Lifetime in the object's proper time.
    #[serde(default)]
    pub proper_lifetime: Option<f64>,
    /// The object at a list of lab times, straight in between.
    #[serde(default)]
    pub keyframes: Option<Vec<KeyframeSpec>>,
    /// Constant proper acceleration from `start`.
    #[serde(default)]
    pub hyperbolic: Option<HyperbolicSpec>,
}

/// The object at one lab time.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyframeSpec {
    /// Lab time.
    pub t: f64,
    /// Lab position of the reference point.
    pub position: DVec3,
    /// Turn of the mesh about its reference point.
    #[serde(default)]
    pub rotation: Option<RotationSpec>,
    /// The mesh's vertices (relative to the reference point, rest-frame
    /// dimensions for a V_obj) at this keyframe, replacing the mesh's own.
    #[serde(default)]
    pub vertices: Option<Vec<DVec3>>,
}

/// A rotation by `degrees` about `axis` (right-handed).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationSpec {
    pub axis: DVec3,
    pub degrees: f64,
}

/// Constant proper acceleration (hyperbolic motion).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HyperbolicSpec {
    /// Proper acceleration of the reference point, 1/l.units (c = 1):
    /// its direction and magnitude.
    pub acceleration: DVec3,
    /// Lab velocity at the start along the acceleration (default 0).
    #[serde(default)]
    pub initial_velocity: f64,
    /// Lab time the motion lasts.
    pub duration: f64,
    /// Largest lab distance of any vertex from its exact path, l.units.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
}

fn default_tolerance() -> f64 {
    1e-4
}

/// One object.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectSpec {
    pub name: String,
    #[serde(default = "h_obj")]
    pub kind: ObjectKind,
    pub mesh: MeshSpec,
    /// Omitted: at rest at `position` for the fixture's `static_lifetime`.
    #[serde(default)]
    pub worldline: Option<WorldlineSpec>,
    /// Position of a static object's reference point.
    #[serde(default)]
    pub position: Option<DVec3>,
    pub material: Material,
}

fn h_obj() -> ObjectKind {
    ObjectKind::HObj
}

/// A whole fixture file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixtureSpec {
    #[serde(default)]
    pub description: String,
    pub camera: CameraSpec,
    pub light: Light,
    #[serde(default = "default_background")]
    pub background: DVec3,
    /// `infinite`, `classical` or `relativistic`.
    #[serde(default = "default_model")]
    pub model: String,
    /// With `infinite`: insert V_obj objects Lorentz-contracted (the fourth combination).
    #[serde(default)]
    pub lorentz: Option<bool>,
    pub image: ImageSpec,
    /// Lab times [t0, t1] during which objects without a worldline exist.
    #[serde(default = "default_static_lifetime")]
    pub static_lifetime: [f64; 2],
    /// How far the fixture's views may differ from their golden images
    /// (default exact: the renderer is deterministic).
    #[serde(default)]
    pub fuzzy: crate::golden::Fuzzy,
    pub objects: Vec<ObjectSpec>,
}

fn default_model() -> String {
    "relativistic".into()
}

/// A loaded, validated fixture: the scene and how to view it.
#[derive(Clone, Debug)]
pub struct Fixture {
    pub name: String,
    pub file: PathBuf,
    pub spec: FixtureSpec,
    pub scene: Scene,
}

/// What to render: the fixture's values, overridden by command-line flags.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    pub model: Option<Model>,
    pub camera_t: Option<f64>,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub spp: Option<u32>,
    /// Turn on Doppler shift / searchlight whatever the fixture says.
    pub doppler: bool,
    pub searchlight: bool,
}

/// A view ready to render.
#[derive(Clone, Copy, Debug)]
pub struct View {
    pub camera: Camera,
    pub camera_t: f64,
    pub model: Model,
    pub settings: RenderSettings,
}

/// The fixtures folder of this workspace.
pub fn fixtures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("vstf lives in the workspace")
        .join("fixtures")
}

/// A path to a fixture file, or the name of one in `fixtures/` (of the
/// current directory, then of this workspace).
pub fn resolve(name_or_path: &str) -> Result<PathBuf, String> {
    let p = Path::new(name_or_path);
    if p.is_file() {
        return Ok(p.to_path_buf());
    }
    let file = format!("{name_or_path}.json");
    for dir in [Path::new("fixtures").to_path_buf(), fixtures_dir()] {
        let candidate = dir.join(&file);
        if candidate.is_file() {
            return Ok(candidate);
        }
    }
    Err(format!(
        "no fixture {name_or_path:?}: not a file, and no {file} in ./fixtures or {}",
        fixtures_dir().display()
    ))
}

/// Names of the fixtures in the workspace's `fixtures/` folder, sorted.
pub fn all_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(fixtures_dir())
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let p = e.path();
            (p.extension()? == "json").then(|| p.file_stem()?.to_str().map(String::from))?
        })
        .collect();
    names.sort();
    names
}

impl Fixture {
    /// Loads a fixture by path or name.
    pub fn load(name_or_path: &str) -> Result<Fixture, FixtureError> {
        let file = resolve(name_or_path).map_err(|message| FixtureError {
            file: PathBuf::from(name_or_path),
            path: String::new(),
            message,
        })?;
        let text = std::fs::read_to_string(&file).map_err(|e| FixtureError {
            file: file.clone(),
            path: String::new(),
            message: format!("cannot read: {e}"),
        })?;
        Fixture::parse(&text, &file)
    }

    /// Parses and validates fixture text; `file` names it in errors and
    /// anchors relative paths (OBJ meshes).
    pub fn parse(text: &str, file: &Path) -> Result<Fixture, FixtureError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let spec: FixtureSpec = serde_path_to_error::deserialize(de).map_err(|e| FixtureError {
            file: file.to_path_buf(),
            path: e.path().to_string(),
            message: e.inner().to_string(),
        })?;
        let fail = |path: String, message: String| FixtureError {
            file: file.to_path_buf(),
            path,
            message,
        };
        let scene = build_scene(&spec, file).map_err(|(p, m)| fail(p, m))?;
        // Insert once with each Lorentz setting, so that errors surface on load.
        for lorentz in [false, true] {
            renderer::Database::build(&scene, lorentz).map_err(|e| {
                let (path, message) = scene_error(&e);
                fail(path, message)
            })?;
        }
        let name = file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("fixture")
            .to_string();
        let fixture = Fixture {
            name,
            file: file.to_path_buf(),
            spec,
            scene,
        };
        fixture
            .view(&Overrides::default())
            .map_err(|(p, m)| fail(p, m))?;
        Ok(fixture)
    }

    /// The model after overrides.
    pub fn model(&self, overrides: &Overrides) -> Result<Model, (String, String)> {
        if let Some(m) = overrides.model {
            return Ok(m);
        }
        let mut m = Model::from_name(&self.spec.model).ok_or_else(|| {
            (
                "model".to_string(),
                format!(
                    "unknown model {:?}: expected infinite, classical or relativistic",
                    self.spec.model
                ),
            )
        })?;
        if let Some(l) = self.spec.lorentz {
            m.lorentz = l;
        }
        Ok(m)
    }

    /// The view after overrides, validated.
    pub fn view(&self, o: &Overrides) -> Result<View, (String, String)> {
        let c = &self.spec.camera;
        let im = &self.spec.image;
        let model = self.model(o)?;
        let camera_t = o.camera_t.unwrap_or(c.t);
        let (width, height) = (o.width.unwrap_or(im.width), o.height.unwrap_or(im.height));
        let spp = o.spp.unwrap_or(im.spp);
        let bad = |p: &str, m: String| Err((p.to_string(), m));
        if !camera_t.is_finite() {
            return bad("camera.t", "must be a finite number".into());
        }
        finite3("camera.position", c.position)?;
        if width == 0
            || height == 0
            || width > MAX_SIDE
            || height > MAX_SIDE
            || u64::from(width) * u64::from(height) > MAX_PIXELS
        {
            return bad(
                "image",
                format!("resolution {width}x{height} is out of range: each side 1..={MAX_SIDE}, at most {MAX_PIXELS} pixels"),
            );
        }
        if spp == 0 || spp > MAX_SPP {
            return bad(
                "image.spp",
                format!("{spp} samples per pixel: expected 1..={MAX_SPP}"),
            );
        }
        if !(im.shutter >= 0.0 && im.shutter.is_finite()) {
            return bad("image.shutter", "must be a finite time >= 0".into());
        }
        if !(c.vfov_deg > 0.0 && c.vfov_deg < 180.0) {
            return bad(
                "camera.vfov_deg",
                format!("{} degrees: expected between 0 and 180", c.vfov_deg),
            );
        }
        let attitude = match (c.look_at, c.yaw_deg, c.pitch_deg) {
            (Some(look_at), None, None) => {
                finite3("camera.look_at", look_at)?;
                finite3("camera.up", c.up)?;
                Attitude::LookAt { look_at, up: c.up }
            }
            (None, yaw, pitch) if yaw.is_some() || pitch.is_some() => {
                let (yaw_deg, pitch_deg) = (yaw.unwrap_or(0.0), pitch.unwrap_or(0.0));
                if !(yaw_deg.is_finite() && pitch_deg.is_finite()) {
                    return bad("camera", "yaw_deg and pitch_deg must be finite".into());
                }
                Attitude::YawPitch { yaw_deg, pitch_deg }
            }
            _ => {
                return bad(
                    "camera",
                    "give either look_at (with optional up) or yaw_deg/pitch_deg".into(),
                )
            }
        };
        let still = Camera::new(
            Event::new(c.t, c.position),
            attitude,
            c.vfov_deg,
            width,
            height,
        )
        .ok_or_else(|| {
            (
                "camera".to_string(),
                "degenerate attitude: look_at equals position, or up is parallel to the view"
                    .to_string(),
            )
        })?;
        let velocity = c.velocity.unwrap_or(DVec3::ZERO);
        finite3("camera.velocity", velocity)?;
        let camera = still.moving(velocity, model).ok_or_else(|| {
            (
                "camera.velocity".to_string(),
                format!(
                    "the camera moves at {:.6}c; it must be slower than light",
                    velocity.length()
                ),
            )
        })?;
        let settings = RenderSettings {
            spp,
            shutter: im.shutter,
            seed: im.seed,
            max_depth: im.max_depth,
            shadows: im.shadows,
            effects: renderer::Effects {
                doppler: im.doppler || o.doppler,
                searchlight: im.searchlight || o.searchlight,
            },
        };
        Ok(View {
            camera,
            camera_t,
            model,
            settings,
        })
    }
}

fn finite3(path: &str, v: DVec3) -> Result<(), (String, String)> {
    if v.is_finite() {
        Ok(())
    } else {
        Err((path.to_string(), "must be finite numbers".to_string()))
    }
}

fn build_mesh(spec: &MeshSpec, path: &str, file: &Path) -> Result<Mesh, (String, String)> {
    let bad = |m: String| Err((path.to_string(), m));
    let positive = |name: &str, v: f64| -> Result<(), (String, String)> {
        if v > 0.0 && v.is_finite() {
            Ok(())
        } else {
            Err((
                format!("{path}.{name}"),
                format!("{v}: expected a positive length"),
            ))
        }
    };
    Ok(match spec {
        MeshSpec::Quad { corner, u, v } => Mesh::quad(*corner, *u, *v),
        MeshSpec::Cuboid { min, max } => {
            if !(min.cmplt(*max).all()) {
                return bad(format!(
                    "cuboid min {min} must be below max {max} on every axis"
                ));
            }
            Mesh::cuboid(*min, *max)
        }
        MeshSpec::Flange {
            height,
            width,
            depth,
        } => {
            positive("flange.height", *height)?;
            positive("flange.width", *width)?;
            positive("flange.depth", *depth)?;
            flange(*height, *width, *depth)
        }
        MeshSpec::BarGrid {
            count,
            spacing,
            first,
            thickness,
            y,
        } => {
            positive("bar_grid.spacing", *spacing)?;
            positive("bar_grid.thickness", *thickness)?;
            if *count == 0 {
                return bad("bar_grid.count must be at least 1".into());
            }
            bar_grid(*count, *spacing, *first, *thickness, *y)
        }
        MeshSpec::Obj { path: p } => {
            let full = file.parent().unwrap_or(Path::new(".")).join(p);
            let text = std::fs::read_to_string(&full).map_err(|e| {
                (
                    format!("{path}.obj.path"),
                    format!("cannot read {}: {e}", full.display()),
                )
            })?;
            Mesh::from_obj(&text).map_err(|e| {
                (
                    format!("{path}.obj.path"),
                    format!("{}: {e}", full.display()),
                )
            })?
        }
        MeshSpec::Triangles { vertices, indices } => Mesh {
            vertices: vertices.clone(),
            triangles: indices.clone(),
        },
        MeshSpec::Sphere { radius, segments } => {
            positive("sphere.radius", *radius)?;
            if *segments < 4 || *segments > 4096 {
                return bad(format!("sphere.segments {segments}: expected 4..=4096"));
            }
            Mesh::uv_sphere(*radius, *segments)
        }
        MeshSpec::AnalyticSphere { radius } => {
            positive("analytic_sphere.radius", *radius)?;
            Mesh::default()
        }
        MeshSpec::Group(parts) => {
            let mut m = Mesh::default();
            for (i, part) in parts.iter().enumerate() {
                m.append(
                    &build_mesh(part, &format!("{path}.group[{i}]"), file)?,
                    DVec3::ZERO,
                );
            }
            m
        }
    })
}

/// A scene error as the JSON path of the object's field and the message.
fn scene_error(e: &SceneError) -> (String, String) {
    use renderer::{HyperbolicField as H, SceneField as F};
    let keyframe = |k: usize| format!("worldline.keyframes[{k}]");
    let field = match e.field {
        F::Shape => "mesh".to_string(),
        F::Motion => "worldline".to_string(),
        F::Start => "worldline.start".to_string(),
        F::Extrusion => "worldline.extrusion".to_string(),
        F::ProperLifetime => "worldline.proper_lifetime".to_string(),
        F::Keyframes => "worldline.keyframes".to_string(),
        F::Keyframe(k) => keyframe(k),
        F::KeyframeTime(k) => format!("{}.t", keyframe(k)),
        F::KeyframePosition(k) => format!("{}.position", keyframe(k)),
        F::KeyframeVertices(k) => format!("{}.vertices", keyframe(k)),
        F::KeyframeVertex {
            keyframe: k,
            vertex,
        } => format!("{}.vertices[{vertex}]", keyframe(k)),
        F::Hyperbolic(h) => format!(
            "worldline.hyperbolic.{}",
            match h {
                H::Start => "start",
                H::Direction => "direction",
                H::Acceleration => "acceleration",
                H::InitialVelocity => "initial_velocity",
                H::Duration => "duration",
                H::Tolerance => "tolerance",
            }
        ),
    };
    (format!("objects[{}].{field}", e.object), e.to_string())
}

fn event(a: [f64; 4]) -> Event {
    Event::new(a[0], DVec3::new(a[1], a[2], a[3]))
}

/// A spectrum's own check, its message naming the field under `path`.
fn spectrum_ok(path: &str, s: Option<&renderer::Spectrum>) -> Result<(), (String, String)> {
    let Some(Err(e)) = s.map(|s| s.validate()) else {
        return Ok(());
    };
    let field = match e.field {
        SpectrumField::Rgb(i) => format!("rgb[{i}]"),
        SpectrumField::GaussianPeak => "gaussian.peak_nm".into(),
        SpectrumField::GaussianWidth => "gaussian.width_nm".into(),
        SpectrumField::GaussianScale => "gaussian.scale".into(),
        SpectrumField::BlackbodyKelvin => "blackbody.kelvin".into(),
        SpectrumField::BlackbodyScale => "blackbody.scale".into(),
        SpectrumField::SampleWavelengths => "samples.nm".into(),
        SpectrumField::SampleValues => "samples.values".into(),
        SpectrumField::SampleWavelength(i) => format!("samples.nm[{i}]"),
        SpectrumField::SampleValue(i) => format!("samples.values[{i}]"),
    };
    Err((path.to_string(), format!("{field}: {}", e.kind)))
}

/// The motion a worldline spec gives; errors name the field under `at`.
fn motion(w: &WorldlineSpec, mesh: &Mesh, at: &str) -> Result<Motion, (String, String)> {
    let field = |f: &str| format!("{at}.{f}");
    let start = |w: &WorldlineSpec| -> Result<Event, (String, String)> {
        let s = w.start.ok_or_else(|| {
            (
                field("start"),
                "missing: the start event [t, x, y, z]".to_string(),
            )
        })?;
        let e = event(s);
        if !e.is_finite() {
            return Err((field("start"), "must be finite numbers".into()));
        }
        Ok(e)
    };
    match (w.extrusion, w.velocity, w.proper_lifetime, &w.keyframes, w.hyperbolic) {
        (Some(e), None, None, None, None) => Ok(Motion::Extrusion {
            start: start(w)?,
            extrusion: FourVector::new(e[0], DVec3::new(e[1], e[2], e[3])),
        }),
        (None, Some(velocity), Some(proper_lifetime), None, None) => Ok(Motion::Velocity {
            start: start(w)?,
            velocity,
            proper_lifetime,
        }),
        (None, None, None, Some(frames), None) => {
            if w.start.is_some() {
                return Err((
                    field("start"),
                    "keyframes give their own positions and times; drop start".into(),
                ));
            }
            let mut keyframes = Vec::with_capacity(frames.len());
            for (k, f) in frames.iter().enumerate() {
                let mut offsets = f.vertices.clone();
                if let Some(r) = f.rotation {
                    let path = field(&format!("keyframes[{k}].rotation"));
                    let axis = r.axis.try_normalize().filter(|_| r.degrees.is_finite()).ok_or_else(|| {
                        (path, "expected a non-zero finite axis and finite degrees".to_string())
                    })?;
                    let turn = glam::DQuat::from_axis_angle(axis, r.degrees.to_radians());
                    let base = offsets.unwrap_or_else(|| mesh.vertices.clone());
                    offsets = Some(base.into_iter().map(|p| turn * p).collect());
                }
                keyframes.push(Keyframe {
                    t: f.t,
                    position: f.position,
                    offsets,
                });
            }
            Ok(Motion::Keyframes(keyframes))
        }
        (None, None, None, None, Some(h)) => {
            let start = start(w)?;
            let a = h.acceleration;
            if !(a.is_finite() && a.length() > 0.0) {
                return Err((
                    field("hyperbolic.acceleration"),
                    "expected a non-zero finite proper acceleration [ax, ay, az] (1/l.units); for uniform motion use velocity".into(),
                ));
            }
            Ok(Motion::Hyperbolic(Hyperbolic {
                start,
                direction: a.normalize(),
                acceleration: a.length(),
                initial_velocity: h.initial_velocity,
                duration: h.duration,
                tolerance: h.tolerance,
            }))
        }
        _ => Err((
            at.to_string(),
            "give one of: extrusion [dt, dx, dy, dz]; velocity [vx, vy, vz] with proper_lifetime; hyperbolic {acceleration, duration}; or keyframes [{t, position}, ...]".into(),
        )),
    }
}

fn build_scene(spec: &FixtureSpec, file: &Path) -> Result<Scene, (String, String)> {
    let [t0, t1] = spec.static_lifetime;
    if !(t0.is_finite() && t1.is_finite() && t0 < t1) {
        return Err((
            "static_lifetime".into(),
            "expected [t0, t1] with t0 < t1, finite".into(),
        ));
    }
    finite3("light.position", spec.light.position)?;
    spectrum_ok("light.spectrum", spec.light.spectrum.as_ref())?;
    let mut objects = Vec::new();
    for (i, o) in spec.objects.iter().enumerate() {
        let at = |f: &str| format!("objects[{i}].{f}");
        let mesh = build_mesh(&o.mesh, &at("mesh"), file)?;
        spectrum_ok(&at("material.spectrum"), o.material.spectrum.as_ref())?;
        spectrum_ok(&at("material.emission"), o.material.emission.as_ref())?;
        let motion = match (&o.worldline, o.position) {
            (None, p) => {
                let p = p.unwrap_or(DVec3::ZERO);
                finite3(&at("position"), p)?;
                Motion::at_rest(p, t0, t1)
            }
            (Some(_), Some(_)) => {
                return Err((
                    at("position"),
                    "give either position (static object) or worldline, not both".into(),
                ))
            }
            (Some(w), None) => motion(w, &mesh, &at("worldline"))?,
        };
        let shape = match o.mesh {
            MeshSpec::AnalyticSphere { radius } => Shape::Sphere { radius },
            _ => Shape::Mesh(mesh),
        };
        objects.push(SceneObject {
            name: o.name.clone(),
            kind: o.kind,
            shape,
            motion,
            material: o.material.clone(),
        });
    }
    Ok(Scene {
        objects,
        light: spec.light.clone(),
        background: spec.background,
    })
}

/// The paper's right-angle flange (4.1.1): two two-sided planes meeting
/// at a right angle along the trailing vertical edge x = 0.
/// The front plane z = `depth` spans x in [0, width]; the side plane
/// x = 0 spans z in [0, depth]; both span y in [0, height].
/// The reference point (origin) is the trailing lower far corner.
pub fn flange(height: f64, width: f64, depth: f64) -> Mesh {
    let mut m = Mesh::quad(
        DVec3::new(0.0, 0.0, depth),
        DVec3::new(width, 0.0, 0.0),
        DVec3::new(0.0, height, 0.0),
    );
    m.append(
        &Mesh::quad(
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, depth),
            DVec3::new(0.0, height, 0.0),
        ),
        DVec3::ZERO,
    );
    m
}

/// Bars of square cross-section `thickness` lying on the plane y = `y`
/// (tops at y, bottoms at y - thickness): `count` bars parallel to z at
/// x = first, first + spacing, ... and `count` parallel to x likewise,
/// each spanning [first - thickness/2, last + thickness/2].
pub fn bar_grid(count: u32, spacing: f64, first: f64, thickness: f64, y: f64) -> Mesh {
    let half = thickness / 2.0;
    let last = first + spacing * f64::from(count.saturating_sub(1));
    let (lo, hi) = (first - half, last + half);
    let mut m = Mesh::default();
    for i in 0..count {
        let c = first + spacing * f64::from(i);
        m.append(
            &Mesh::cuboid(
                DVec3::new(c - half, y - thickness, lo),
                DVec3::new(c + half, y, hi),
            ),
            DVec3::ZERO,
        );
        m.append(
            &Mesh::cuboid(
                DVec3::new(lo, y - thickness, c - half),
                DVec3::new(hi, y, c + half),
            ),
            DVec3::ZERO,
        );
    }
    m
}
