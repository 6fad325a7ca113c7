//! The workspace's integration tests, built as one binary (linking the
//! renderer and the VSTF once rather than once per file). Modules follow the
//! flow: the 4D database and the rays that meet it, the images rendered from
//! it, and the VSTF harness that measures and judges them.

// Float comparisons everywhere use approx's macros with explicit tolerances.
#[macro_use]
extern crate approx;

/// Temporal extrusion, light-cone intersection, analytic spheres and
/// keyframed motion: what the 4D database holds and what rays find in it.
mod spacetime {
    mod keyframes;
    mod lightcone;
    mod packets;
    mod sphere;
    mod storage;
    mod watertight;
}

/// Whole images and the shading of their pixels: light-speed models,
/// determinism (whatever the vector level), retarded positions, shadows,
/// mirrors, motion blur and clocks.
mod rendering {
    mod bent;
    mod render;
    mod shading;
    mod simd;
    mod sky;
    mod spectral;
    mod textures;
}

/// The VSTF itself: fixture errors, the per-pixel debug log, the checks
/// with their snapshotted table and golden images, and the measurements'
/// and oracle's own models against the renderer's.
mod harness {
    mod born_rigid;
    mod debug;
    mod debug_diff;
    mod declared;
    mod declared_motion;
    mod emulator;
    mod face_materials;
    mod fixture_errors;
    mod gltf;
    mod grid_line;
    mod independent_models;
    mod lensing;
    mod mirrors;
    mod redshift;
    mod rocket;
    mod rocket_errors;
    mod rocket_keyframes;
    mod rocket_keyframes_checks;
    mod rocket_keyframes_shutter;
    mod shapiro;
    mod shared_worldline;
    mod spinning;
    mod surface_frame;
    mod two_sided;
    mod vstf_check;
}
