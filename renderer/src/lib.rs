//! A minimal spacetime ray tracer after Black et al., "Viewing Classical and
//! Relativistic Spacetime Geometry".
//!
//! Data flows one way:
//!
//! 1. `scene`: 3D objects as given ([`Scene`], [`SceneObject`] with its
//!    [`Shape`], [`Motion`], [`Material`]), a point [`Light`], in `spacetime`
//!    terms ([`Event`], [`FourVector`], [`Boost`], [`Ray`]).
//! 2. `geometry`: temporal extrusion of every triangle along its object's
//!    path into a prism of three [`Tetrahedron`]s (paper 3.1), keyframed and
//!    accelerated paths first resolved into poses; analytic spheres kept
//!    exact; the ray tests ([`Hit`]): a prism of uniform motion whole, as its
//!    triangle at rest in the comoving frame within its lab times, and a
//!    keyframe interval's tetrahedra by the barycentric solve (paper 3.2).
//! 3. `database`: the static 4D [`Database`] of all prisms, built once
//!    (paper 3, items 1-2), each object's path cut into straight
//!    stretches, searched through `accel`, a two-level bounding volume
//!    hierarchy over 4D boxes.
//! 4. `camera`: rays on the camera's past light cone ([`Camera`]; the
//!    light-speed [`Model`] of paper 4.1.5).
//! 5. `shading`: Lambert and Phong with shadow and mirror rays on light
//!    cones ([`Shader`]), with the colour effects of motion ([`Effects`])
//!    on `color` spectra ([`Spectrum`]).
//! 6. `render`: pixels to an [`Image`], with 4D anti-aliasing; `trace`
//!    records every step of a pixel for the debug mode.
//!
//! Natural units throughout (c = 1); events are lab-frame (t, x, y, z) in f64,
//! y up, the stage in the x-z plane.
//!
//! # Example
//!
//! A cube moving at 0.5c seen by a camera at rest: the camera at lab time 0
//! sees the light the cube sent about 4 time units earlier, when it was in
//! front of the camera.
//!
//! ```
//! use glam::DVec3;
//! use renderer::{
//!     render, Attitude, Camera, Database, Event, FourVector, Light, Material, Mesh, Model,
//!     Motion, ObjectKind, RenderSettings, Scene, SceneObject, Shape, Spacetime,
//! };
//!
//! // A 2 x 2 x 2 cube (rest frame) moving along +x at 0.5c, centred on
//! // the origin at t = -4.
//! let cube = SceneObject {
//!     name: "cube".into(),
//!     kind: ObjectKind::VObj,
//!     shape: Shape::Mesh(Mesh::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0))),
//!     motion: Motion::Extrusion {
//!         start: Event::new(-20.0, DVec3::new(-8.0, 0.0, 0.0)),
//!         extrusion: FourVector::new(40.0, DVec3::new(20.0, 0.0, 0.0)),
//!     },
//!     material: Material::matte(DVec3::new(0.8, 0.5, 0.2)),
//!     face_materials: Vec::new(),
//! };
//! let scene = Scene {
//!     objects: vec![cube],
//!     light: Light {
//!         position: DVec3::new(0.0, 10.0, 10.0),
//!         color: DVec3::ONE,
//!         ambient: 0.3,
//!         spectrum: None,
//!     },
//!     background: DVec3::ZERO,
//!     sky: None,
//!     spacetime: Spacetime::Flat,
//! };
//! let model = Model::RELATIVISTIC;
//! let db = Database::build(&scene, model.lorentz)?;
//! let at = Event::new(0.0, DVec3::new(0.0, 0.0, 5.0));
//! let look = Attitude::LookAt { look_at: DVec3::ZERO, up: DVec3::Y };
//! let camera = Camera::new(at, look, 60.0, 16, 12).expect("a valid attitude");
//! let image = render(&db, &scene, &camera, 0.0, model, &RenderSettings::default());
//! let pixel = |x: u32, y: u32| image.pixels[(y * image.width + x) as usize];
//! assert_ne!(pixel(8, 6), scene.background, "the cube is seen in the middle");
//! assert_eq!(pixel(0, 0), scene.background, "and not in the corner");
//! # Ok::<(), renderer::SceneError>(())
//! ```

mod accel;
mod camera;
mod color;
mod database;
mod geometry;
mod math;
mod render;
mod rng;
mod scene;
mod shading;
mod simd;
mod spacetime;
mod trace;

pub use camera::{Attitude, Camera, CameraWorldline, Kinematics, Model};
pub use color::{
    band_nm, chromaticity, cmf, xyz, xyz_to_rgb, Spectrum, SpectrumError, SpectrumErrorKind,
    SpectrumField, BAND_LEN,
};
pub use database::{Database, Packing, Traversal};
pub use geometry::{Barycentric, Hit, PrimitiveId, Tetrahedron};
pub use render::{
    pixel, pixel_traced, render, render_reusing, render_stoppable, render_window, shader, Frame,
    Image, RenderSettings, Window,
};
pub use rng::SplitMix64;
pub use scene::{
    Axes, Blink, Hyperbolic, HyperbolicField, Keyframe, Light, Material, Mesh, MeshError, Motion,
    ObjectKind, Scene, SceneError, SceneErrorKind, SceneField, SceneObject, Shape, Texels, Texture,
    UvMapping,
};
pub use shading::{BackgroundBand, BentEnd, Effects, Found, Shader};
pub use simd::SimdLevel;
pub use spacetime::{
    Boost, Event, FourVector, Geodesic, Leg, LightSpeed, Ray, Schwarzschild, Spacetime, Waypoint,
    WaypointWindow, CHORD_TOLERANCE, MAX_CHORDS, MAX_WINDOW_WAYPOINTS, SKY_TOLERANCE,
};
pub use trace::{Outcome, RayKind, Recorder, Step, Trace};
