//! A check suite split into shards ([`crate::shard`]): each shard checks
//! the fixtures whose names hash to it and stores its reports (rows, golden
//! comparisons, the views' images and markers, the golden and diff images
//! the report shows) in a folder with its manifest; [`merge`] reads every
//! shard's folder back into the reports an unsharded run gives, for the
//! table, the JSON and the HTML report.

use crate::check::findings::{FixtureReport, ViewReport};
use crate::golden::{slug, Comparison};
use crate::project::Project;
use crate::shard::{Manifest, Shard};
use crate::Row;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A view as stored: its image in a file beside the report.
#[derive(Serialize, Deserialize)]
struct StoredView {
    name: String,
    image: String,
    markers: Vec<(f64, f64)>,
    rows: Vec<String>,
    measured: Vec<String>,
}

/// A fixture's report as stored; paths relative to the shard's folder.
#[derive(Serialize, Deserialize)]
struct StoredReport {
    fixture: String,
    description: String,
    views: Vec<StoredView>,
    rows: Vec<Row>,
    goldens: Vec<Comparison>,
    declared_views: Vec<String>,
}

/// A hash of what a check's results depend on: the fixtures chosen, each
/// fixture file's bytes and its golden images' bytes, so that shards of
/// different projects (or of one project at different commits) are not
/// merged.
pub fn scene_hash(project: &Project, chosen: &[String]) -> String {
    let store = project.store();
    let mut all = Vec::new();
    for name in chosen {
        all.extend_from_slice(name.as_bytes());
        all.push(0);
        if let Ok(file) = project.resolve(name) {
            all.extend(std::fs::read(file).unwrap_or_default());
        }
        let dir = store.golden.join(slug(name));
        let mut goldens: Vec<PathBuf> = std::fs::read_dir(&dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "png"))
            .collect();
        goldens.sort();
        for g in goldens {
            all.extend(g.file_name().unwrap_or_default().as_encoded_bytes());
            all.extend(std::fs::read(g).unwrap_or_default());
        }
    }
    crate::shard::hash_hex(&all)
}

/// The folder shard `shard`'s results go in, under `dir`.
pub fn shard_dir(dir: &Path, shard: Shard) -> PathBuf {
    dir.join(format!("check-{}", shard.tag()))
}

/// Copies `from` into `dir` as `name`, returning `name`.
fn keep(from: &Path, dir: &Path, name: String) -> Result<String, String> {
    let bytes = std::fs::read(from).map_err(|e| format!("cannot read {}: {e}", from.display()))?;
    crate::output::write_atomic(&dir.join(&name), &bytes)
        .map_err(|e| format!("cannot write {}: {e}", dir.join(&name).display()))?;
    Ok(name)
}

/// Stores one fixture's report in `dir`, recording every file in `m`.
fn store_report(r: &FixtureReport, dir: &Path, m: &mut Manifest) -> Result<(), String> {
    let base = slug(&r.fixture);
    let mut views = Vec::new();
    for v in &r.views {
        let file = format!("{base}--{}.png", slug(&v.name));
        crate::output::write_png(&dir.join(&file), &v.image)?;
        m.add(dir, r.fixture.clone(), &file)?;
        views.push(StoredView {
            name: v.name.clone(),
            image: file,
            markers: v.markers.clone(),
            rows: v.rows.clone(),
            measured: v.measured.clone(),
        });
    }
    let mut goldens = Vec::new();
    for g in &r.goldens {
        let mut g = g.clone();
        let view = slug(&g.view);
        if let Some(golden) = g.golden.take() {
            let name = keep(&golden, dir, format!("{base}--{view}-golden.png"))?;
            m.add(dir, r.fixture.clone(), &name)?;
            g.golden = Some(name.into());
        }
        if let Some(pending) = g.pending.take() {
            let diff = pending.join("diff.png");
            if diff.is_file() {
                let folder = format!("{base}--{view}-pending");
                std::fs::create_dir_all(dir.join(&folder))
                    .map_err(|e| format!("cannot create {}: {e}", dir.join(&folder).display()))?;
                let name = keep(&diff, dir, format!("{folder}/diff.png"))?;
                m.add(dir, r.fixture.clone(), &name)?;
                g.pending = Some(folder.into());
            }
        }
        goldens.push(g);
    }
    let stored = StoredReport {
        fixture: r.fixture.clone(),
        description: r.description.clone(),
        views,
        rows: r.rows.clone(),
        goldens,
        declared_views: r.declared_views.clone(),
    };
    let file = format!("{base}.json");
    let text = serde_json::to_string_pretty(&stored).expect("reports serialise");
    crate::output::write_atomic(&dir.join(&file), text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", dir.join(&file).display()))?;
    m.add(dir, r.fixture.clone(), &file)
}

/// Removes the JSON files (reports and manifest) an earlier run of a shard
/// wrote in its folder `own`: file by file, never a recursive delete, so a
/// link or another file there is left as it is.
fn clear_reports(own: &Path) -> Result<(), String> {
    for e in std::fs::read_dir(own).into_iter().flatten().flatten() {
        let json = e.path().extension().is_some_and(|x| x == "json");
        if json && e.file_type().is_ok_and(|t| t.is_file()) {
            std::fs::remove_file(e.path())
                .map_err(|err| format!("cannot clear {}: {err}", e.path().display()))?;
        }
    }
    Ok(())
}

/// Stores shard `shard`'s `reports` (of a job of `items` fixtures, results
/// depending on `scene`) in its folder under `dir`, with its manifest;
/// returns the manifest's path.
pub fn store(
    reports: &[FixtureReport],
    dir: &Path,
    (shard, scene, items): (Shard, String, usize),
) -> Result<PathBuf, String> {
    let own = shard_dir(dir, shard);
    clear_reports(&own)?;
    std::fs::create_dir_all(&own).map_err(|e| format!("cannot create {}: {e}", own.display()))?;
    let mut m = Manifest::new("check", scene, shard, items);
    for r in reports {
        store_report(r, &own, &mut m)?;
    }
    m.write(&own)
}

/// Reads one stored report back, its paths made absolute again.
fn load_report(dir: &Path, file: &str) -> Result<FixtureReport, String> {
    let path = dir.join(file);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let s: StoredReport = serde_json::from_str(&text)
        .map_err(|e| format!("{}: not a stored report: {e}", path.display()))?;
    let mut views = Vec::new();
    for v in s.views {
        let p = dir.join(&v.image);
        let image = image::open(&p)
            .map_err(|e| format!("cannot read {}: {e}", p.display()))?
            .to_rgb8();
        views.push(ViewReport {
            name: v.name,
            image,
            markers: v.markers,
            rows: v.rows,
            measured: v.measured,
        });
    }
    let goldens = s
        .goldens
        .into_iter()
        .map(|mut g| {
            g.golden = g.golden.map(|p| dir.join(p));
            g.pending = g.pending.map(|p| dir.join(p));
            g
        })
        .collect();
    Ok(FixtureReport {
        fixture: s.fixture,
        description: s.description,
        views,
        rows: s.rows,
        goldens,
        declared_views: s.declared_views,
    })
}

/// The reports of the shards whose manifests are `found` (read from the
/// folders of [`with_shard_folders`]), once all N shards are there, of one
/// suite and unchanged: the fixtures in the order of their names.
pub fn merge(found: Vec<crate::shard::Found>) -> Result<Vec<FixtureReport>, String> {
    let shards = crate::shard::complete(found, "check")?;
    let mut reports: Vec<FixtureReport> = Vec::new();
    for s in &shards {
        for w in s
            .manifest
            .outputs
            .iter()
            .filter(|w| w.file.ends_with(".json"))
        {
            let r = load_report(&s.dir, &w.file)?;
            if reports.iter().any(|x| x.fixture == r.fixture) {
                return Err(format!(
                    "fixture {:?} is in more than one shard (again in shard {})",
                    r.fixture, s.manifest.shard
                ));
            }
            reports.push(r);
        }
    }
    let items = shards[0].manifest.items;
    if reports.len() != items {
        return Err(format!(
            "the shards hold {} fixtures, but the suite has {items}",
            reports.len()
        ));
    }
    reports.sort_by(|a, b| a.fixture.cmp(&b.fixture));
    Ok(reports)
}

/// The folders `dirs`, each followed by its `check-I-of-N` subfolders
/// (where `vstf check --shard` stores a shard under its `--shard-dir`).
pub fn with_shard_folders(dirs: &[PathBuf]) -> Vec<PathBuf> {
    let mut all = Vec::new();
    for d in dirs {
        all.push(d.clone());
        let mut subs: Vec<PathBuf> = std::fs::read_dir(d)
            .into_iter()
            .flatten()
            .flatten()
            .filter(|e| e.file_name().to_string_lossy().starts_with("check-"))
            .map(|e| e.path())
            .filter(|p| p.is_dir())
            .collect();
        subs.sort();
        all.extend(subs);
    }
    all
}
