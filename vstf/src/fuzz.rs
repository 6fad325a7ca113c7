//! Fuzzing the fixture path: structured mutations of seed fixtures run
//! through parsing, validation (the declared checks included), the
//! database build and a tiny render. Bad input must come back as an error;
//! a panic, a non-finite pixel or an input that takes too long is a
//! failure.
//!
//! The same [`one`] runs under cargo-fuzz (`fuzz/`, with a nightly
//! toolchain) and under the stable, seeded, time-bounded [`run`] that
//! `vstf fuzz` and `.ci/run` use. Each input is derived from the seed and
//! its index alone, so a run is reproducible whatever the thread count.

use crate::budget::Budget;
use crate::error::Error;
use crate::fixture::{Fixture, Overrides};
use renderer::{SplitMix64, Traversal};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The budget inputs run within: small, so that no input can take long.
const FUZZ_BUDGET: Budget = Budget {
    memory: 200_000_000,
    seconds: 1.0,
};

/// Longest an input may take before the run fails as hung.
pub const HANG: Duration = Duration::from_secs(20);

/// How an input ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Refused with an error (the right answer to bad input).
    Refused,
    /// Loaded and rendered.
    Rendered,
    /// A failure: a panic or a non-finite pixel, with what was seen.
    Failed(String),
}

/// Runs one input (fixture text, possibly broken) through the fixture path.
pub fn one(text: &str) -> Outcome {
    let file = Path::new("fuzz/input.json");
    let fixture = match Fixture::parse_within(text, file, &FUZZ_BUDGET) {
        Ok(f) => f,
        Err(_) => return Outcome::Refused,
    };
    let tiny = Overrides {
        width: Some(12),
        height: Some(9),
        spp: Some(1),
        ..Overrides::default()
    };
    let Ok(view) = crate::run::view(&fixture, &tiny) else {
        return Outcome::Refused;
    };
    match crate::run::render(&fixture, &view, Traversal::Bvh) {
        Ok(image) if image.pixels.iter().all(|p| p.is_finite()) => Outcome::Rendered,
        Ok(_) => Outcome::Failed("a non-finite pixel was returned".into()),
        Err(e @ Error::NonFinite { .. }) => Outcome::Failed(e.to_string()),
        Err(_) => Outcome::Refused,
    }
}

/// Input number `index` of the run seeded `seed`: a seed fixture with a few
/// structured mutations (numbers made extreme, values of another type,
/// keys removed or added, array elements dropped or repeated), and now and
/// then a byte-level one of its text.
pub fn input(seeds: &[Value], seed: u64, index: u64) -> String {
    let mut rng = SplitMix64::new(seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let mut v = seeds[(rng.next_u64() % seeds.len() as u64) as usize].clone();
    let mutations = 1 + rng.next_u64() % 4;
    for _ in 0..mutations {
        mutate(&mut v, &mut rng);
    }
    let mut text = v.to_string();
    if rng.next_u64() % 8 == 0 && !text.is_empty() {
        let at = (rng.next_u64() % text.len() as u64) as usize;
        if text.is_char_boundary(at) {
            let c = b"{}[]\",:0-e9 x"[(rng.next_u64() % 13) as usize] as char;
            text.insert(at, c);
        }
    }
    text
}

/// Applies one mutation at a random node of `v`.
fn mutate(v: &mut Value, rng: &mut SplitMix64) {
    let node = pick(v, rng);
    let choice = rng.next_u64() % 8;
    match (choice, node) {
        (0..=2, n @ Value::Number(_)) => *n = extreme(rng),
        (3, n) => *n = other_type(rng),
        (4, Value::Object(m)) if !m.is_empty() => {
            let k = m
                .keys()
                .nth((rng.next_u64() % m.len() as u64) as usize)
                .cloned();
            if let Some(k) = k {
                m.remove(&k);
            }
        }
        (5, Value::Object(m)) => {
            m.insert(format!("key{}", rng.next_u64() % 10), extreme(rng));
        }
        (6, Value::Array(a)) if !a.is_empty() => {
            let i = (rng.next_u64() % a.len() as u64) as usize;
            if rng.next_u64() % 2 == 0 {
                a.remove(i);
            } else {
                let copy = a[i].clone();
                a.push(copy);
            }
        }
        (_, n @ Value::Number(_)) => *n = extreme(rng),
        (_, n) => *n = other_type(rng),
    }
}

/// A random node of `v` (descending at random, stopping at random).
fn pick<'v>(v: &'v mut Value, rng: &mut SplitMix64) -> &'v mut Value {
    let go_on = rng.next_u64() % 5 != 0;
    let len = match &*v {
        Value::Object(m) => m.len(),
        Value::Array(a) => a.len(),
        _ => 0,
    };
    if !go_on || len == 0 {
        return v;
    }
    let i = (rng.next_u64() % len as u64) as usize;
    match v {
        Value::Object(m) => pick(m.values_mut().nth(i).expect("in range"), rng),
        Value::Array(a) => pick(&mut a[i], rng),
        _ => unreachable!("only objects and arrays have children"),
    }
}

/// A number from the edges of what fixtures meet: zero, signs, huge, tiny,
/// integers at type limits, and plain random values.
fn extreme(rng: &mut SplitMix64) -> Value {
    const EDGES: [f64; 14] = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        1e308,
        -1e308,
        1e-308,
        4294967295.0,
        4294967296.0,
        1e9,
        -1e9,
        0.999999999,
        1.000000001,
    ];
    let k = (rng.next_u64() % (EDGES.len() as u64 + 2)) as usize;
    let x = match EDGES.get(k) {
        Some(e) => *e,
        None => rng.range(-100.0, 100.0),
    };
    if x.fract() == 0.0 && x.abs() < 1e15 {
        Value::from(x as i64)
    } else {
        Value::from(x)
    }
}

/// A value of a random other type.
fn other_type(rng: &mut SplitMix64) -> Value {
    match rng.next_u64() % 6 {
        0 => Value::Null,
        1 => Value::Bool(true),
        2 => Value::from("x"),
        3 => Value::Array(vec![]),
        4 => Value::Object(Default::default()),
        _ => Value::from(vec![extreme(rng), extreme(rng), extreme(rng)]),
    }
}

/// What a run found.
#[derive(Debug, Default)]
pub struct Summary {
    /// Inputs run.
    pub inputs: u64,
    /// Inputs refused with an error.
    pub refused: u64,
    /// Inputs loaded and rendered.
    pub rendered: u64,
    /// Failures: the saved input and what happened.
    pub failures: Vec<(PathBuf, String)>,
    /// The slowest input, seconds.
    pub slowest: f64,
    /// Wall time of the run, seconds.
    pub seconds: f64,
}

/// The seed fixtures: every JSON file in `dirs` (the corpus and a
/// project's fixtures).
pub fn seeds(dirs: &[PathBuf]) -> Result<Vec<Value>, String> {
    let mut out = Vec::new();
    for dir in dirs {
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|e| format!("{}: {e}", dir.display()))?
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .collect();
        files.sort();
        for f in files {
            let text = std::fs::read_to_string(&f).map_err(|e| format!("{}: {e}", f.display()))?;
            out.push(serde_json::from_str(&text).map_err(|e| format!("{}: {e}", f.display()))?);
        }
    }
    if out.is_empty() {
        return Err("no seed fixtures".into());
    }
    Ok(out)
}

/// What a worker is doing, for the watchdog: the input it runs and when it
/// started (milliseconds since the run began, plus one; 0 when idle).
#[derive(Default)]
struct Busy {
    index: AtomicU64,
    since_ms: AtomicU64,
}

/// The run's shared state.
struct Shared<'a> {
    target: &'a (dyn Fn(&str) -> Outcome + Sync),
    seeds: &'a [Value],
    seed: u64,
    next: AtomicU64,
    stop: AtomicBool,
    started: Instant,
    save: &'a Path,
    results: std::sync::Mutex<Summary>,
}

/// Runs inputs 0, 1, 2, ... of `seed` for `seconds` (or `max_inputs`),
/// on every thread, catching panics; failing inputs are saved in `save`.
/// A watchdog ends the process if an input runs longer than [`HANG`],
/// saving that input too.
pub fn run(seeds: &[Value], seed: u64, seconds: f64, max_inputs: u64, save: &Path) -> Summary {
    // Caught panics are counted, not printed one by one.
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let summary = run_target(&one, seeds, seed, (seconds, max_inputs), save);
    std::panic::set_hook(previous_hook);
    summary
}

/// [`run`] with another target than [`one`] (for testing the runner),
/// leaving the panic hook alone.
pub fn run_target(
    target: &(dyn Fn(&str) -> Outcome + Sync),
    seeds: &[Value],
    seed: u64,
    (seconds, max_inputs): (f64, u64),
    save: &Path,
) -> Summary {
    let shared = Shared {
        target,
        seeds,
        seed,
        next: AtomicU64::new(0),
        stop: AtomicBool::new(false),
        started: Instant::now(),
        save,
        results: std::sync::Mutex::new(Summary::default()),
    };
    let threads = rayon::current_num_threads().max(1);
    let busy: Vec<Busy> = (0..threads).map(|_| Busy::default()).collect();
    let finished = AtomicBool::new(false);
    std::thread::scope(|s| {
        s.spawn(|| watchdog(&shared, &busy, &finished));
        let workers: Vec<_> = busy
            .iter()
            .map(|b| s.spawn(|| worker(&shared, (seconds, max_inputs), b)))
            .collect();
        for w in workers {
            let _ = w.join();
        }
        finished.store(true, Ordering::Relaxed);
    });
    let mut summary = shared.results.into_inner().unwrap_or_default();
    summary.seconds = shared.started.elapsed().as_secs_f64();
    summary
}

/// Ends the process, saving the input, when a worker has run one input
/// longer than [`HANG`].
fn watchdog(shared: &Shared, busy: &[Busy], finished: &AtomicBool) {
    while !finished.load(Ordering::Relaxed) {
        let now = shared.started.elapsed().as_millis() as u64 + 1;
        for b in busy {
            let since = b.since_ms.load(Ordering::Relaxed);
            if since != 0 && now.saturating_sub(since) > HANG.as_millis() as u64 {
                let index = b.index.load(Ordering::Relaxed);
                let path = shared
                    .save
                    .join(format!("seed-{}-hang-{index}.json", shared.seed));
                let text = input(shared.seeds, shared.seed, index);
                let _ = crate::output::write_atomic(&path, text.as_bytes());
                eprintln!(
                    "fuzz: input {index} still running after {} s: saved as {}",
                    HANG.as_secs(),
                    path.display()
                );
                std::process::exit(3);
            }
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// One thread of [`run`]: takes input numbers until the time or count is up.
fn worker(shared: &Shared, (seconds, max_inputs): (f64, u64), busy: &Busy) {
    while !shared.stop.load(Ordering::Relaxed) && shared.started.elapsed().as_secs_f64() < seconds {
        let index = shared.next.fetch_add(1, Ordering::Relaxed);
        if index >= max_inputs {
            break;
        }
        let text = input(shared.seeds, shared.seed, index);
        busy.index.store(index, Ordering::Relaxed);
        busy.since_ms.store(
            shared.started.elapsed().as_millis() as u64 + 1,
            Ordering::Relaxed,
        );
        let t = Instant::now();
        let run = std::panic::AssertUnwindSafe(|| (shared.target)(&text));
        let outcome = std::panic::catch_unwind(run).unwrap_or_else(|p| {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "a panic".into());
            Outcome::Failed(format!("panicked: {msg}"))
        });
        busy.since_ms.store(0, Ordering::Relaxed);
        record(shared, index, &text, outcome, t.elapsed().as_secs_f64());
    }
}

/// Counts an input's outcome; a failure saves the input and stops the run.
fn record(shared: &Shared, index: u64, text: &str, outcome: Outcome, took: f64) {
    let mut r = shared.results.lock().unwrap_or_else(|e| e.into_inner());
    r.inputs += 1;
    r.slowest = r.slowest.max(took);
    match outcome {
        Outcome::Refused => r.refused += 1,
        Outcome::Rendered => r.rendered += 1,
        Outcome::Failed(why) => {
            let path = shared
                .save
                .join(format!("seed-{}-input-{index}.json", shared.seed));
            let _ = crate::output::write_atomic(&path, text.as_bytes());
            r.failures.push((path, why));
            shared.stop.store(true, Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_are_reproducible_and_varied() {
        let seeds = vec![serde_json::json!({"a": [1, 2, {"b": 0.5}], "c": "x"})];
        assert_eq!(input(&seeds, 7, 3), input(&seeds, 7, 3));
        let distinct: std::collections::HashSet<String> =
            (0..50).map(|i| input(&seeds, 7, i)).collect();
        assert!(distinct.len() > 20, "{}", distinct.len());
    }

    #[test]
    fn broken_text_is_refused_not_a_failure() {
        assert_eq!(one("{"), Outcome::Refused);
        assert_eq!(one("null"), Outcome::Refused);
    }

    #[test]
    fn a_panicking_input_is_caught_saved_and_stops_the_run() {
        let save = std::env::temp_dir().join(format!("vstf-fuzz-{}", std::process::id()));
        let seeds = vec![serde_json::json!({"a": [1, 2, 3], "b": {"c": 0.5}})];
        let target = |text: &str| {
            if text.contains("null") {
                panic!("found a null");
            }
            Outcome::Refused
        };
        let s = run_target(&target, &seeds, 3, (30.0, 10_000), &save);
        // Each worker stops at its first failure (so one per thread at most).
        assert!(!s.failures.is_empty(), "{s:?}");
        for (path, why) in &s.failures {
            assert!(why.contains("panicked: found a null"), "{why}");
            assert!(std::fs::read_to_string(path).unwrap().contains("null"));
        }
        assert!(s.inputs < 10_000, "the run went on after the failure");
        let clean = run_target(&|_: &str| Outcome::Rendered, &seeds, 3, (30.0, 500), &save);
        assert_eq!(
            (clean.inputs, clean.rendered, clean.failures.len()),
            (500, 500, 0)
        );
        std::fs::remove_dir_all(&save).ok();
    }
}
