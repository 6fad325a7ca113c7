//! The `vstf` command line.

use clap::{Parser, Subcommand};
use renderer::{LightSpeed, Model, Traversal};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;
use vstf::fixture::{Fixture, Overrides};

#[derive(Parser)]
#[command(
    name = "vstf",
    version,
    about = "Visual Software Test Fixture for a spacetime ray tracer"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum ModelArg {
    Infinite,
    Classical,
    Relativistic,
}

/// Flags that override a fixture's view.
#[derive(clap::Args, Clone, Debug)]
struct ViewArgs {
    /// Light-speed model (default: the fixture's).
    #[arg(long, value_enum)]
    model: Option<ModelArg>,
    /// Insert V_obj objects Lorentz-transformed (with --model infinite: the
    /// contracted objects as they are at t_c).
    #[arg(long)]
    lorentz: bool,
    /// Camera lab time, t.units.
    #[arg(long, allow_hyphen_values = true)]
    camera_t: Option<f64>,
    /// Image width, pixels.
    #[arg(long)]
    width: Option<u32>,
    /// Image height, pixels.
    #[arg(long)]
    height: Option<u32>,
    /// Samples per pixel (4D anti-aliasing).
    #[arg(long)]
    spp: Option<u32>,
    /// Doppler-shift the colours: spectral rendering, wavelengths followed
    /// along each leg of the light's path (off by default: it can hide the
    /// geometry).
    #[arg(long)]
    doppler: bool,
    /// Scale intensities by the searchlight effect (powers of the Doppler
    /// factor; see docs/physics.md).
    #[arg(long)]
    searchlight: bool,
}

impl ViewArgs {
    fn overrides(&self, fixture: &Fixture) -> Result<Overrides, String> {
        Ok(Overrides {
            model: model_of(self.model, self.lorentz, fixture)?,
            camera_t: self.camera_t,
            width: self.width,
            height: self.height,
            spp: self.spp,
            doppler: self.doppler,
            searchlight: self.searchlight,
        })
    }
}

#[derive(Subcommand)]
enum Command {
    /// Render one view of a fixture to a PNG.
    Render {
        /// A fixture JSON file, or the name of one in fixtures/.
        fixture: String,
        /// Output PNG.
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        view: ViewArgs,
        /// Test every tetrahedron for every ray (no acceleration structure).
        #[arg(long)]
        brute_force: bool,
    },
    /// Render every fixture (or the named ones), measure the images and check
    /// them against first-principles physics; exits non-zero if a row fails.
    Check {
        /// Fixture names (default: all checked fixtures).
        fixtures: Vec<String>,
        /// Also write the rows as a JSON array to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Also write a static HTML report (index.html and images) into this folder.
        #[arg(long)]
        report: Option<PathBuf>,
        /// Smaller probes and fewer samples (what `cargo test` uses).
        #[arg(long)]
        quick: bool,
    },
    /// Approve pending images (from failed or missing golden comparisons of
    /// `vstf check`) as the new golden images. Refused when CI is set.
    Approve {
        /// Fixtures whose pending images to approve.
        fixtures: Vec<String>,
        /// Approve every pending image.
        #[arg(long, conflicts_with = "fixtures")]
        all: bool,
        /// Only list what is pending.
        #[arg(long, conflicts_with_all = ["fixtures", "all"])]
        list: bool,
    },
    /// Print every variable along one pixel's rays, or log a region's pixels
    /// as JSON lines.
    Debug {
        /// A fixture JSON file, or the name of one in fixtures/.
        fixture: String,
        /// The pixel to trace, X,Y (from the top left).
        #[arg(long, value_parser = parse_pair, required_unless_present = "region", conflicts_with = "region")]
        pixel: Option<(u32, u32)>,
        /// A region to log, X0,Y0,X1,Y1 (inclusive).
        #[arg(long, value_parser = parse_region, requires = "log")]
        region: Option<(u32, u32, u32, u32)>,
        /// Write one JSON object per pixel to this file.
        #[arg(long)]
        log: Option<PathBuf>,
        #[command(flatten)]
        view: ViewArgs,
        /// Test every tetrahedron for every ray (no acceleration structure).
        #[arg(long)]
        brute_force: bool,
    },
    /// Compare two debug logs; exits non-zero when they differ beyond the tolerance.
    DebugDiff {
        a: PathBuf,
        b: PathBuf,
        /// Relative tolerance on numbers: |a - b| <= tol * max(1, |a|, |b|).
        #[arg(long, default_value_t = 0.0)]
        tol: f64,
        /// Skip steps of this kind (e.g. candidate, which a change of traversal changes).
        #[arg(long)]
        ignore: Vec<String>,
        /// How many differing pixels to print.
        #[arg(long, default_value_t = 10)]
        show: usize,
    },
    /// Render an animation: frames differ only by the camera's t, and the 4D
    /// database is built once.
    Animate {
        /// A fixture JSON file, or the name of one in fixtures/.
        fixture: String,
        /// Camera times A..B (inclusive).
        #[arg(long, value_parser = vstf::animate::parse_range, allow_hyphen_values = true)]
        frames: (f64, f64),
        /// Camera time between frames, t.units.
        #[arg(long, default_value_t = 1.0)]
        step: f64,
        /// A folder (PNG sequence), FILE.gif (animated GIF) or FILE.png (APNG).
        #[arg(long)]
        out: PathBuf,
        /// Frames per second of the GIF or APNG.
        #[arg(long, default_value_t = 10)]
        fps: u32,
        #[command(flatten)]
        view: ViewArgs,
    },
    /// Measure rendering speed: rays per second, relativistic against
    /// infinite light speed, BVH against brute force, growth with scene size,
    /// build time and memory.
    Bench {
        /// Small images and scenes (a smoke test, not figures to quote).
        #[arg(long)]
        quick: bool,
    },
    /// List the fixtures in fixtures/.
    List,
}

fn model_of(
    arg: Option<ModelArg>,
    lorentz: bool,
    fixture: &Fixture,
) -> Result<Option<Model>, String> {
    let base = match arg {
        Some(ModelArg::Infinite) => Some(Model::INFINITE),
        Some(ModelArg::Classical) => Some(Model::CLASSICAL),
        Some(ModelArg::Relativistic) => Some(Model::RELATIVISTIC),
        None if lorentz => Some(
            fixture
                .model(&Overrides::default())
                .map_err(|(p, m)| format!("{p}: {m}"))?,
        ),
        None => None,
    };
    Ok(base.map(|m| Model {
        lorentz: m.lorentz || lorentz,
        ..m
    }))
}

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

/// Loads a fixture, applies the view flags and builds the database.
fn prepare(
    name: &str,
    args: &ViewArgs,
    brute_force: bool,
) -> Result<(Fixture, vstf::fixture::View, renderer::Database), String> {
    let fixture = Fixture::load(name).map_err(|e| e.to_string())?;
    let view = vstf::run::view(&fixture, &args.overrides(&fixture)?)?;
    let traversal = if brute_force {
        Traversal::BruteForce
    } else {
        Traversal::Bvh
    };
    let db = vstf::run::database(&fixture, view.model.lorentz, traversal)?;
    Ok((fixture, view, db))
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Render {
            fixture,
            out,
            view,
            brute_force,
        } => {
            let started = Instant::now();
            let (fixture, view, db) = prepare(&fixture, &view, brute_force)?;
            let image = vstf::run::render_with(&db, &fixture, &view);
            vstf::output::write_png(&out, &image.to_rgb8())?;
            eprintln!(
                "rendered {} ({} model{}, t_c = {}, {}x{}, {} spp, {} tetrahedra) in {:.2} s -> {}",
                fixture.name,
                view.model,
                if view.model.light_speed == LightSpeed::Infinite {
                    ", lab slice"
                } else {
                    ""
                },
                view.camera_t,
                view.camera.width,
                view.camera.height,
                view.settings.spp,
                db.tetrahedra().len(),
                started.elapsed().as_secs_f64(),
                out.display()
            );
            Ok(())
        }
        Command::Check {
            fixtures,
            json,
            report,
            quick,
        } => {
            let effort = if quick {
                vstf::check::Effort::QUICK
            } else {
                vstf::check::Effort::FULL
            };
            let started = Instant::now();
            let store = vstf::golden::Store::workspace();
            let reports = vstf::check::run(&fixtures, &effort, &store)?;
            let rows: Vec<vstf::check::Row> = reports.iter().flat_map(|r| r.rows.clone()).collect();
            print!("{}", vstf::report::table(&rows));
            let goldens: Vec<&vstf::golden::Comparison> =
                reports.iter().flat_map(|r| &r.goldens).collect();
            for g in &goldens {
                println!("{g}");
            }
            let failed = goldens.iter().filter(|g| !g.pass).count();
            println!("golden: {} passed, {failed} failed", goldens.len() - failed);
            if failed > 0 {
                eprintln!("golden images differ or are missing: look at the pending images under {}, then `vstf approve --list` and `vstf approve FIXTURE...` if the change is right", store.pending.display());
            }
            eprintln!(
                "checked {} fixtures in {:.1} s",
                reports.len(),
                started.elapsed().as_secs_f64()
            );
            if let Some(path) = json {
                vstf::output::write_atomic(&path, vstf::report::json(&rows).as_bytes())
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            }
            if let Some(dir) = report {
                vstf::report::html(&dir, &reports)?;
                eprintln!("report: {}", dir.join("index.html").display());
            }
            if rows.iter().any(|r| !r.pass) || failed > 0 {
                return Err("some checks failed".into());
            }
            Ok(())
        }
        Command::Approve {
            fixtures,
            all,
            list,
        } => {
            let store = vstf::golden::Store::workspace();
            if list {
                let pending = store.list_pending();
                if pending.is_empty() {
                    println!("nothing pending");
                }
                for p in pending {
                    let what = if p.replaces { "changed" } else { "new" };
                    println!(
                        "{what:8} {} / {}  {}",
                        p.fixture,
                        p.view,
                        p.actual.display()
                    );
                }
                return Ok(());
            }
            if fixtures.is_empty() && !all {
                return Err("name the fixtures to approve, or give --all (see --list)".into());
            }
            let ci = std::env::var_os("CI").is_some();
            let chosen = if all { None } else { Some(fixtures.as_slice()) };
            let done = store.approve(chosen, ci)?;
            if done.is_empty() {
                println!("nothing to approve");
            }
            for p in done {
                let what = if p.replaces { "updated" } else { "created" };
                println!(
                    "{what} {}",
                    store.golden_path(&p.fixture, &p.view).display()
                );
            }
            Ok(())
        }
        Command::Debug {
            fixture,
            pixel,
            region,
            log,
            view,
            brute_force,
        } => {
            let (fixture, view, db) = prepare(&fixture, &view, brute_force)?;
            let (x0, y0, x1, y1) = match (pixel, region) {
                (Some((x, y)), _) => (x, y, x, y),
                (None, Some(r)) => r,
                (None, None) => unreachable!("clap requires --pixel or --region"),
            };
            let mut lines = String::new();
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let entry = vstf::debug::trace_pixel(&fixture, &view, &db, x, y)?;
                    if pixel.is_some() {
                        print!("{}", vstf::debug::describe(&entry));
                    }
                    lines.push_str(&serde_json::to_string(&entry).map_err(|e| e.to_string())?);
                    lines.push('\n');
                }
            }
            if let Some(path) = log {
                vstf::output::write_atomic(&path, lines.as_bytes())
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                eprintln!(
                    "logged {} pixels to {}",
                    lines.lines().count(),
                    path.display()
                );
            }
            Ok(())
        }
        Command::DebugDiff {
            a,
            b,
            tol,
            ignore,
            show,
        } => {
            let read = |p: &PathBuf| {
                std::fs::read_to_string(p).map_err(|e| format!("cannot read {}: {e}", p.display()))
            };
            let diffs = vstf::debug::diff_logs(&read(&a)?, &read(&b)?, tol, &ignore)?;
            for d in diffs.iter().take(show) {
                println!(
                    "line {} pixel {}: {}: {} vs {}",
                    d.line, d.pixel, d.path, d.a, d.b
                );
            }
            if diffs.is_empty() {
                println!("the logs agree (tolerance {tol})");
                Ok(())
            } else {
                Err(format!("{} pixels differ", diffs.len()))
            }
        }
        Command::Animate {
            fixture,
            frames,
            step,
            out,
            fps,
            view,
        } => {
            use std::sync::atomic::{AtomicBool, Ordering};
            use std::sync::Arc;
            if view.camera_t.is_some() {
                return Err("animate takes its camera times from --frames, not --camera-t".into());
            }
            let times = vstf::animate::frame_times(frames.0, frames.1, step)?;
            let fixture = Fixture::load(&fixture).map_err(|e| e.to_string())?;
            let overrides = Overrides {
                camera_t: Some(times[0]),
                ..view.overrides(&fixture)?
            };
            let view = vstf::run::view(&fixture, &overrides)?;
            let output = vstf::animate::Output::from_path(&out);
            let stop = Arc::new(AtomicBool::new(false));
            let flag = stop.clone();
            ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst))
                .map_err(|e| format!("cannot handle Ctrl-C: {e}"))?;
            let started = Instant::now();
            let db = vstf::run::database(&fixture, view.model.lorentz, Traversal::Bvh)?;
            let build = started.elapsed().as_secs_f64();
            let bar = indicatif::ProgressBar::new(times.len() as u64);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:40} {pos}/{len} frames  {per_sec}  {elapsed} elapsed, {eta} left",
                )
                .expect("a valid template"),
            );
            let done =
                vstf::animate::render_frames(&fixture, &view, &db, &times, &output, &stop, |n| {
                    bar.set_position(n as u64)
                })?;
            bar.finish_and_clear();
            let dir = output.frames_dir();
            if done < times.len() {
                return Err(format!(
                    "interrupted: {done} of {} frames finished, in {}",
                    times.len(),
                    dir.display()
                ));
            }
            vstf::animate::finish(&output, done, fps)?;
            eprintln!(
                "animated {} ({} frames, t = {}..{} step {step}, {} model, {}x{}): database built once in {build:.2} s, {:.2} s in all -> {}",
                fixture.name,
                done,
                frames.0,
                frames.1,
                view.model,
                view.camera.width,
                view.camera.height,
                started.elapsed().as_secs_f64(),
                out.display()
            );
            Ok(())
        }
        Command::Bench { quick } => {
            print!("{}", vstf::bench::run(quick)?);
            Ok(())
        }
        Command::List => {
            for name in vstf::fixture::all_names() {
                let desc = Fixture::load(&name)
                    .map(|f| f.spec.description)
                    .unwrap_or_else(|e| format!("(invalid: {e})"));
                println!("{name:24} {desc}");
            }
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
