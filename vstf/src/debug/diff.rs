//! Comparing two ray logs (`vstf debug-diff`): the first field that
//! differs at each pixel, within a tolerance, skipping chosen step kinds.

use serde_json::Value;

/// The kinds of steps a log holds (the `step` tag of each), which
/// `debug-diff --ignore` may skip.
pub const STEP_KINDS: [&str; 10] = [
    "sample",
    "ray",
    "candidate",
    "hit",
    "miss",
    "shading",
    "doppler",
    "reflection",
    "gravitational",
    "observed",
];

/// The first field that differs between two logs' pixel, and how many did.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    /// Line number (1-based) in the logs.
    pub line: usize,
    /// The pixel, as written in the log (`[x,y]`).
    pub pixel: String,
    /// JSON path of the first differing field, with the kind of its step,
    /// e.g. `steps[4] (hit).event.t`.
    pub path: String,
    /// Its value in the first log.
    pub a: String,
    /// Its value in the second log.
    pub b: String,
    /// Every differing field of the pixel (path, first, second), the first
    /// of them included; only the first with `first_only`.
    pub fields: Vec<(String, String, String)>,
}

/// How two logs compare: the differing pixels kept (the first `keep`), how
/// many differ in all, and how many lines each log has.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Comparison {
    /// The first differing pixels, in order.
    pub shown: Vec<Difference>,
    /// All differing pixels (a different number of lines counts as one).
    pub differing: usize,
    /// Lines in the first and the second log.
    pub lines: (usize, usize),
}

/// How a comparison of logs treats numbers and steps: numbers agree when
/// |a - b| <= tol * max(1, |a|, |b|); steps of the kinds in `ignore` are
/// skipped; `first_only` keeps only each pixel's first differing field.
pub struct DiffOptions<'a> {
    /// The relative tolerance.
    pub tol: f64,
    /// Step kinds skipped (each one of [`STEP_KINDS`]).
    pub ignore: &'a [String],
    /// Only the first differing field of each pixel.
    pub first_only: bool,
    /// How many differing pixels to keep.
    pub keep: usize,
}

/// Compares two JSON-lines logs pixel by pixel, reading both a line at a
/// time (constant memory whatever their size).
pub fn diff_streams(
    a: impl std::io::BufRead,
    b: impl std::io::BufRead,
    o: &DiffOptions,
) -> Result<Comparison, String> {
    if let Some(bad) = o.ignore.iter().find(|k| !STEP_KINDS.contains(&k.as_str())) {
        return Err(format!(
            "--ignore {bad:?}: no such step kind (the kinds: {})",
            STEP_KINDS.join(", ")
        ));
    }
    let mut out = Comparison::default();
    let (mut la, mut lb) = (a.lines(), b.lines());
    let parse = |line: Option<std::io::Result<String>>,
                 which: &str,
                 n: usize|
     -> Result<Option<Value>, String> {
        match line {
            None => Ok(None),
            Some(Err(e)) => Err(format!("{which} line {n}: {e}")),
            Some(Ok(l)) => serde_json::from_str(&l)
                .map(Some)
                .map_err(|e| format!("{which} line {n}: {e}")),
        }
    };
    loop {
        let n = out.lines.0.max(out.lines.1) + 1;
        let (x, y) = (
            parse(la.next(), "first log", n)?,
            parse(lb.next(), "second log", n)?,
        );
        out.lines.0 += usize::from(x.is_some());
        out.lines.1 += usize::from(y.is_some());
        let (x, y) = match (x, y) {
            (Some(x), Some(y)) => (x, y),
            (None, None) => break,
            _ => {
                // One log ends: count the rest of the other.
                out.lines.0 += la.by_ref().count();
                out.lines.1 += lb.by_ref().count();
                out.differing += 1;
                if out.shown.len() < o.keep {
                    let (a, b) = (out.lines.0.to_string(), out.lines.1.to_string());
                    out.shown.push(Difference {
                        line: n,
                        pixel: "-".into(),
                        path: "(number of pixels)".into(),
                        fields: vec![("(number of pixels)".into(), a.clone(), b.clone())],
                        a,
                        b,
                    });
                }
                break;
            }
        };
        let (x, y) = (strip(&x, o.ignore), strip(&y, o.ignore));
        let mut fields = Vec::new();
        differences(&x, &y, "", o, &mut fields);
        if let Some((path, a, b)) = fields.first().cloned() {
            out.differing += 1;
            if out.shown.len() < o.keep {
                out.shown.push(Difference {
                    line: n,
                    pixel: x["pixel"].to_string(),
                    path,
                    a,
                    b,
                    fields,
                });
            }
        }
    }
    Ok(out)
}

/// Compares two JSON-lines logs held in memory: the first differing field
/// of every differing pixel (see [`diff_streams`]).
pub fn diff_logs(a: &str, b: &str, tol: f64, ignore: &[String]) -> Result<Vec<Difference>, String> {
    let o = DiffOptions {
        tol,
        ignore,
        first_only: true,
        keep: usize::MAX,
    };
    Ok(diff_streams(a.as_bytes(), b.as_bytes(), &o)?.shown)
}

fn strip(v: &Value, ignore: &[String]) -> Value {
    let mut v = v.clone();
    if let Some(steps) = v.get_mut("steps").and_then(Value::as_array_mut) {
        steps.retain(|s| {
            !s["step"]
                .as_str()
                .is_some_and(|k| ignore.iter().any(|i| i == k))
        });
    }
    v
}

/// The most fields of one pixel listed.
const MAX_FIELDS: usize = 64;

/// Appends every field where `a` and `b` differ (only the first with
/// `first_only`), with its path; a step's path names its kind.
fn differences(
    a: &Value,
    b: &Value,
    path: &str,
    o: &DiffOptions,
    out: &mut Vec<(String, String, String)>,
) {
    let full = |out: &Vec<_>| out.len() >= MAX_FIELDS || (o.first_only && !out.is_empty());
    if full(out) {
        return;
    }
    let here = |out: &mut Vec<(String, String, String)>| {
        let p = if path.is_empty() {
            ".".into()
        } else {
            path.to_string()
        };
        out.push((p, a.to_string(), b.to_string()));
    };
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (
                x.as_f64().unwrap_or(f64::NAN),
                y.as_f64().unwrap_or(f64::NAN),
            );
            let agree = (x - y).abs() <= o.tol * 1f64.max(x.abs()).max(y.abs());
            if !agree {
                here(out);
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                let kind = match (path, p["step"].as_str(), q["step"].as_str()) {
                    ("steps", Some(k), Some(l)) if k != l => {
                        // Steps of different kinds: one difference, not their fields.
                        out.push((
                            format!("{path}[{i}] (kind of step)"),
                            k.to_string(),
                            l.to_string(),
                        ));
                        if full(out) {
                            return;
                        }
                        continue;
                    }
                    ("steps", Some(k), _) => format!(" ({k})"),
                    _ => String::new(),
                };
                differences(p, q, &format!("{path}[{i}]{kind}"), o, out);
                if full(out) {
                    return;
                }
            }
            if x.len() != y.len() {
                out.push((
                    format!("{path} (length)"),
                    x.len().to_string(),
                    y.len().to_string(),
                ));
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort();
            keys.dedup();
            for k in keys {
                let sub = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                match (x.get(k), y.get(k)) {
                    (Some(p), Some(q)) => differences(p, q, &sub, o, out),
                    (p, q) => out.push((sub, format!("{p:?}"), format!("{q:?}"))),
                }
                if full(out) {
                    return;
                }
            }
        }
        _ if a == b => {}
        _ => here(out),
    }
}
