//! The command line's grammar: subcommands, their flags and the parsers of
//! flag values. Each `///` on a flag is its `--help` text.

use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "vstf",
    version,
    about = "Visual Software Test Fixture for a spacetime ray tracer"
)]
pub struct Cli {
    /// The project folder (default: the nearest ancestor of the current
    /// directory holding vstf.toml or fixtures/).
    #[arg(long, global = true, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// The widest vector level the searches may use: `baseline` (the
    /// build's own target) or `x86-64-v3` (AVX2, where the CPU has it; the
    /// default). The images are the same to the bit either way.
    #[arg(long, global = true, value_name = "LEVEL", value_parser = simd_level)]
    pub simd: Option<renderer::SimdLevel>,
    #[command(subcommand)]
    pub command: Command,
}

/// What `--simd` names.
fn simd_level(text: &str) -> Result<renderer::SimdLevel, String> {
    renderer::SimdLevel::from_name(text).ok_or_else(|| {
        let names = renderer::SimdLevel::ALL.map(renderer::SimdLevel::name);
        format!("expected {}", names.join(" or "))
    })
}

// What `render --models` names.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum ModelsArg {
    /// Infinite, classical and relativistic, side by side.
    All,
}

// What `--model` names: the light-speed model to render with.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum ModelArg {
    Infinite,
    Classical,
    Relativistic,
}

/// Flags that override a fixture's view.
#[derive(clap::Args, Clone, Debug)]
pub struct ViewArgs {
    /// Light-speed model (default: the fixture's).
    #[arg(long, value_enum)]
    pub model: Option<ModelArg>,
    /// Insert V_obj objects Lorentz-transformed (with --model infinite: the
    /// contracted objects as they are at t_c).
    #[arg(long)]
    pub lorentz: bool,
    /// Camera lab time, t.units; `auto`: the light time from the looked-at
    /// point; `auto:OBJECT`: when OBJECT is seen crossing the line of sight.
    #[arg(long, allow_hyphen_values = true, value_parser = str::parse::<vstf::CameraTime>)]
    pub camera_t: Option<vstf::CameraTime>,
    /// Image width, pixels.
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height, pixels.
    #[arg(long)]
    pub height: Option<u32>,
    /// Samples per pixel (4D anti-aliasing).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Doppler-shift the colours: spectral rendering, wavelengths followed
    /// along each leg of the light's path (off by default: it can hide the
    /// geometry).
    #[arg(long)]
    pub doppler: bool,
    /// Scale intensities by the searchlight effect (powers of the Doppler
    /// factor; see docs/physics.md).
    #[arg(long)]
    pub searchlight: bool,
    /// Go on beyond the work and memory budget (8 GB of database, an hour of
    /// rendering by the estimate printed when it is refused).
    #[arg(long)]
    pub force: bool,
    /// A view the fixture declares, exactly as `vstf check` renders it for
    /// its golden image (camera time, model, size, samples, colour effects).
    #[arg(long, conflicts_with_all = ["model", "lorentz", "camera_t", "width", "height", "spp", "doppler", "searchlight"])]
    pub view: Option<String>,
}

#[derive(Subcommand)]
pub enum Command {
    /// Render one view of a fixture to a PNG, JPEG or OpenEXR file (with
    /// --aovs: the EXR also holds each pixel's event time, proper time,
    /// Doppler and searchlight factors, object, distance and normal).
    Render(RenderArgs),
    /// Render every fixture (or the named ones), measure the images and check
    /// them against first-principles physics; exits non-zero if a row fails.
    Check(CheckArgs),
    /// Approve pending images (from failed or missing golden comparisons of
    /// `vstf check`) as the new golden images. Refused when CI is set.
    Approve(ApproveArgs),
    /// Reject pending images: drop them, leaving the golden images as they are.
    Reject(RejectArgs),
    /// Review the pending images one at a time: accept, reject or skip each
    /// (answers read from stdin). Refused when CI is set.
    Review,
    /// Print every variable along one pixel's rays, or log a region's pixels
    /// as JSON lines.
    Debug(DebugArgs),
    /// Compare two debug logs; exits non-zero when they differ beyond the tolerance.
    DebugDiff(DebugDiffArgs),
    /// Render an animation: frames differ only by the camera's t, and the 4D
    /// database is built once.
    Animate(AnimateArgs),
    /// Assemble the outputs of sharded runs (`animate --shard`, `check
    /// --shard`) once every shard is there: refuses gaps, duplicates and
    /// shards of another scene or version.
    Merge(MergeArgs),
    /// Measure rendering speed: rays per second, relativistic against
    /// infinite light speed, BVH against brute force, growth with scene size,
    /// build time and memory.
    Bench {
        /// Small images and scenes (a smoke test, not figures to quote).
        #[arg(long)]
        quick: bool,
        /// (Internal) measure one fixture's load, build, frames and peak
        /// memory in this process and print them as JSON.
        #[arg(long, hide = true)]
        measure: Option<PathBuf>,
        /// (Internal) with --measure: trace this fixture's frames in turn
        /// with the measured one's, in this process, and print both as JSON.
        #[arg(long, hide = true, requires = "measure")]
        against: Option<PathBuf>,
        /// (Internal) frames rendered by --measure.
        #[arg(long, hide = true, default_value_t = 1)]
        frames: usize,
    },
    /// Serve a local page (127.0.0.1 only) for looking at every view:
    /// render, golden and diff, flip, approve and reject, camera-time and
    /// speed sliders, a model switch, and a pixel's debug variables on a click.
    Serve {
        /// The port (0: any free one; the address is printed).
        #[arg(long, default_value_t = 8117)]
        port: u16,
        /// The memory kept for built scenes, MB; the least recently used
        /// is dropped beyond it.
        #[arg(long, default_value_t = 512)]
        cache_mb: u64,
    },
    /// List the fixtures in fixtures/.
    List {
        /// Also list each fixture's declared views (what `--view` takes).
        #[arg(long)]
        views: bool,
    },
    /// Fuzz the fixture path (parse, validate, build, tiny render) with
    /// seeded mutations of the corpus and the project's fixtures; fails on
    /// a panic, a non-finite pixel or a hang.
    Fuzz(FuzzArgs),
    /// Start a project in DIR (default: here): vstf.toml, a fixture with
    /// declared checks, .gitignore and README; nothing existing is overwritten.
    Init(InitArgs),
}

// The argument structs below carry `//`, not `///`: clap would take a doc
// comment for the subcommand's help, which the `Command` variant gives.

// `vstf render`.
#[derive(clap::Args)]
pub struct RenderArgs {
    /// A fixture JSON file, or the name of one in fixtures/.
    pub fixture: String,
    /// The image file, by its extension: .png or .jpg/.jpeg (8 bits a
    /// channel, the linear values as the golden PNGs hold them), or .exr
    /// (OpenEXR: the linear radiance as float32 R, G, B).
    #[arg(long)]
    pub out: PathBuf,
    /// With an .exr output: also write per-pixel layers, float32, read from
    /// the ray through each pixel's centre: event_t (lab time of the event
    /// seen, the retarded time), proper_time (the object's own time there),
    /// doppler (nu_camera / nu_surface), searchlight (D^4), object (index in
    /// the fixture's objects), distance (from the camera at the camera time)
    /// and normal.X/Y/Z. Where nothing is hit: object -1, the others NaN.
    #[arg(long, conflicts_with = "models")]
    pub aovs: bool,
    /// `all`: the three models side by side, labelled, each at its own
    /// camera time (infinite at the time the others' light left the
    /// looked-at point).
    #[arg(long, value_enum, conflicts_with_all = ["model", "view"])]
    pub models: Option<ModelsArg>,
    #[command(flatten)]
    pub view: ViewArgs,
    /// Test every prism and tetrahedron for every ray (no acceleration structure).
    #[arg(long)]
    pub brute_force: bool,
}

// `vstf check`.
#[derive(clap::Args)]
pub struct CheckArgs {
    /// Fixture names (default: all checked fixtures).
    pub fixtures: Vec<String>,
    /// Also write the rows as a JSON array to this file (`-`: to stdout, the
    /// table then going to stderr).
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Also write a static HTML report (index.html and images) into this folder.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Smaller probes and fewer samples (what `cargo test` uses).
    #[arg(long)]
    pub quick: bool,
    /// Load fixtures beyond the memory budget (8 GB of database).
    #[arg(long)]
    pub force: bool,
    /// Print the full table (fixture and paper columns, untruncated names)
    /// and every golden image's line, not only the failing ones.
    #[arg(long, short)]
    pub verbose: bool,
    /// Check only shard I of N (the fixtures whose name hashes to I-1
    /// modulo N) and store its results for `vstf merge`; `N` alone takes I
    /// from SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or
    /// AWS_BATCH_JOB_ARRAY_INDEX.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Where a shard stores its results (in check-I-of-N/).
    #[arg(long, default_value = "target/vstf/shards", requires = "shard")]
    pub shard_dir: PathBuf,
}

// `vstf fuzz`.
#[derive(clap::Args)]
pub struct FuzzArgs {
    /// How long to run, seconds.
    #[arg(long, default_value_t = 60.0)]
    pub seconds: f64,
    /// The seed the inputs are derived from.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Stop after this many inputs.
    #[arg(long)]
    pub max_inputs: Option<u64>,
    /// Where failing inputs are saved (default: target/fuzz-failures of the project).
    #[arg(long)]
    pub save: Option<PathBuf>,
}

// `vstf init`.
#[derive(clap::Args)]
pub struct InitArgs {
    /// The project folder (created if needed; default: the current directory).
    pub dir: Option<PathBuf>,
}

// `vstf approve`.
#[derive(clap::Args)]
pub struct ApproveArgs {
    /// What to approve: FIXTURE (all its pending views) or FIXTURE/VIEW.
    pub fixtures: Vec<String>,
    /// Approve every pending image.
    #[arg(long, conflicts_with = "fixtures")]
    pub all: bool,
    /// Only list what is pending.
    #[arg(long, conflicts_with_all = ["fixtures", "all"])]
    pub list: bool,
}

// `vstf reject`.
#[derive(clap::Args)]
pub struct RejectArgs {
    /// What to reject: FIXTURE (all its pending views) or FIXTURE/VIEW.
    #[arg(required_unless_present = "all")]
    pub fixtures: Vec<String>,
    /// Reject every pending image.
    #[arg(long, conflicts_with = "fixtures")]
    pub all: bool,
}

// `vstf debug`.
#[derive(clap::Args)]
pub struct DebugArgs {
    /// A fixture JSON file, or the name of one in fixtures/.
    pub fixture: String,
    /// The pixel to trace, X,Y (from the top left).
    #[arg(long, value_parser = parse_pair, required_unless_present = "region", conflicts_with = "region")]
    pub pixel: Option<(u32, u32)>,
    /// A region to log, X0,Y0,X1,Y1 (inclusive).
    #[arg(long, value_parser = parse_region, requires = "log")]
    pub region: Option<(u32, u32, u32, u32)>,
    /// Write one JSON object per pixel to this file.
    #[arg(long)]
    pub log: Option<PathBuf>,
    #[command(flatten)]
    pub view: ViewArgs,
    /// Test every prism and tetrahedron for every ray (no acceleration structure).
    #[arg(long)]
    pub brute_force: bool,
    /// Also print and log every prism and tetrahedron tested and why it was rejected
    /// (long: hundreds of lines a pixel).
    #[arg(long)]
    pub candidates: bool,
}

// `vstf debug-diff`.
#[derive(clap::Args)]
pub struct DebugDiffArgs {
    pub a: PathBuf,
    pub b: PathBuf,
    /// Relative tolerance on numbers: |a - b| <= tol * max(1, |a|, |b|).
    #[arg(long, default_value_t = 0.0, value_parser = parse_tolerance, allow_hyphen_values = true)]
    pub tol: f64,
    /// Skip steps of this kind (e.g. candidate, which a change of traversal changes).
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(vstf::debug::STEP_KINDS))]
    pub ignore: Vec<String>,
    /// How many differing pixels to print.
    #[arg(long, default_value_t = 10)]
    pub show: usize,
    /// Only the first differing field of each pixel.
    #[arg(long)]
    pub first: bool,
}

// `vstf animate`. Its frames set the camera time, so the view flags'
// --camera-t is neither listed nor taken.
#[derive(clap::Args)]
#[command(mut_arg("camera_t", |a| a.hide(true)))]
pub struct AnimateArgs {
    /// A fixture JSON file, or the name of one in fixtures/.
    pub fixture: String,
    /// Camera times A..B (inclusive): lab times (`A..B` or `t:A..B`), or
    /// the proper times of a camera with a worldline (`tau:A..B`).
    #[arg(long, value_parser = vstf::animate::parse_frames, allow_hyphen_values = true)]
    pub frames: vstf::animate::FrameRange,
    /// Camera time between frames, t.units (on the clock `--frames` names).
    #[arg(long, default_value_t = 1.0)]
    pub step: f64,
    /// A folder (PNG sequence), FILE.gif (animated GIF), FILE.png (APNG),
    /// or FILE.mp4 (H.264) / FILE.webm (VP9) encoded by ffmpeg from PATH
    /// (frames rendered into FILE.frames/ beside it, removed once encoded).
    /// Other file extensions (.jpg, .mov, ...) are refused.
    #[arg(long)]
    pub out: PathBuf,
    /// Frames per second of the GIF, APNG or video.
    #[arg(long, default_value_t = 10)]
    pub fps: u32,
    /// Keep the frames an interrupted run of the same animation wrote whole
    /// (its frames folder), and render only the rest.
    #[arg(long)]
    pub resume: bool,
    /// Write each frame's camera time on it ("t = 12.5", top left).
    #[arg(long)]
    pub label: bool,
    /// Render only shard I of N (frames whose index is I-1 modulo N) into
    /// the frames folder, with its manifest, for `vstf merge`; `N` alone
    /// takes I from SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or
    /// AWS_BATCH_JOB_ARRAY_INDEX.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    #[command(flatten)]
    pub view: ViewArgs,
}

// `vstf merge`.
#[derive(clap::Args)]
pub struct MergeArgs {
    /// Folders the shards wrote (their manifests, shard-I-of-N.json, are
    /// found in them or, for checks, in their check-I-of-N subfolders).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// The assembled animation: a folder (PNG sequence), FILE.gif,
    /// FILE.png (APNG), FILE.mp4 or FILE.webm (by ffmpeg from PATH).
    /// Needed for animations.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Frames per second of the GIF, APNG or video.
    #[arg(long, default_value_t = 10)]
    pub fps: u32,
    /// For checks: also write the merged rows and golden results as JSON
    /// (`-`: to stdout).
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// For checks: also write the merged HTML report into this folder.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// For checks: the full table and every golden image's line.
    #[arg(long, short)]
    pub verbose: bool,
}

/// Parses `--tol`: a finite, non-negative number.
fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t >= 0.0 => Ok(t),
        _ => Err(format!("{s:?}: expected a finite tolerance of 0 or more")),
    }
}

/// Parses `--pixel X,Y`.
fn parse_pair(s: &str) -> Result<(u32, u32), String> {
    let v: Vec<u32> = s
        .split(',')
        .map(|p| {
            p.trim()
                .parse::<u32>()
                .map_err(|_| format!("{s:?}: expected X,Y"))
        })
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x, y] => Ok((x, y)),
        _ => Err(format!("{s:?}: expected X,Y")),
    }
}

/// Parses `--region X0,Y0,X1,Y1`, corners in order.
fn parse_region(s: &str) -> Result<(u32, u32, u32, u32), String> {
    let v: Vec<u32> = s
        .split(',')
        .map(|p| {
            p.trim()
                .parse::<u32>()
                .map_err(|_| format!("{s:?}: expected X0,Y0,X1,Y1"))
        })
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x0, y0, x1, y1] if x0 <= x1 && y0 <= y1 => Ok((x0, y0, x1, y1)),
        _ => Err(format!(
            "{s:?}: expected X0,Y0,X1,Y1 with X0 <= X1 and Y0 <= Y1"
        )),
    }
}
