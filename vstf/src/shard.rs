//! Long animations and check suites split over the array jobs of an
//! existing batch engine (Slurm job arrays, Kubernetes Indexed Jobs, AWS
//! Batch array jobs): shard I of N (1-based, as cargo-nextest's
//! `--partition`) renders the frames whose index is I - 1 modulo N, or
//! checks the fixtures whose name hashes to I - 1 modulo N. Each shard
//! writes a manifest (what was rendered, from which scene, by which
//! version, and a hash of every output) that `vstf merge` reads to refuse
//! gaps, duplicates and mismatched scenes before assembling the whole.
//! The assignment and the hashes are stable: the same on every machine.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The manifest format, bumped when its meaning changes.
pub const FORMAT: &str = "vstf shard 1";

/// The environment variables an array job's index is read from when
/// `--shard` names only the count, with the index each one starts from.
pub const INDEX_VARIABLES: [(&str, usize); 3] = [
    ("SLURM_ARRAY_TASK_ID", 1),
    ("JOB_COMPLETION_INDEX", 0),
    ("AWS_BATCH_JOB_ARRAY_INDEX", 0),
];

/// Shard `index` of `count` (1 <= index <= count).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Which shard, from 1.
    pub index: usize,
    /// How many shards there are.
    pub count: usize,
}

impl Shard {
    /// The whole job in one shard.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// `I/N`, or `N` with the index from the batch engine's environment
    /// (`env` looks a variable up): Slurm's `SLURM_ARRAY_TASK_ID` counted
    /// from `SLURM_ARRAY_TASK_MIN` (from 1 when that is unset), Kubernetes'
    /// `JOB_COMPLETION_INDEX` and AWS Batch's `AWS_BATCH_JOB_ARRAY_INDEX`
    /// from 0.
    pub fn parse(arg: &str, env: impl Fn(&str) -> Option<String>) -> Result<Shard, String> {
        let number = |s: &str, what: &str| {
            s.trim()
                .parse::<usize>()
                .map_err(|_| format!("--shard {arg:?}: {what} {s:?} is not a whole number"))
        };
        let (index, count) = match arg.split_once('/') {
            Some((i, n)) => (number(i, "the index")?, number(n, "the count")?),
            None => {
                let count = number(arg, "the count")?;
                (index_from_env(&env)?, count)
            }
        };
        if count == 0 || index == 0 || index > count {
            return Err(format!(
                "--shard {arg:?}: shard {index} of {count}: the index runs from 1 to the count"
            ));
        }
        Ok(Shard { index, count })
    }

    /// Whether this shard renders frame `i` (from 0).
    pub fn owns_frame(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }

    /// Whether this shard checks the fixture named `name`.
    pub fn owns_fixture(&self, name: &str) -> bool {
        (stable_hash(name.as_bytes()) % self.count as u64) as usize == self.index - 1
    }

    /// `I-of-N`, for file names.
    pub fn tag(&self) -> String {
        format!("{}-of-{}", self.index, self.count)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The 1-based index of this array job, from the first of
/// [`INDEX_VARIABLES`] that is set.
fn index_from_env(env: &impl Fn(&str) -> Option<String>) -> Result<usize, String> {
    for (var, first) in INDEX_VARIABLES {
        let Some(value) = env(var) else { continue };
        let parse = |v: &str, name: &str| {
            v.trim()
                .parse::<usize>()
                .map_err(|_| format!("{name}={v:?}: not a whole number"))
        };
        let id = parse(&value, var)?;
        let from = match (var, env("SLURM_ARRAY_TASK_MIN")) {
            ("SLURM_ARRAY_TASK_ID", Some(min)) => parse(&min, "SLURM_ARRAY_TASK_MIN")?,
            _ => first,
        };
        return id
            .checked_sub(from)
            .map(|k| k + 1)
            .ok_or_else(|| format!("{var}={id}: below the array's first index {from}"));
    }
    let names: Vec<&str> = INDEX_VARIABLES.iter().map(|(v, _)| *v).collect();
    Err(format!(
        "--shard N needs the shard's index: give --shard I/N, or run as an array job ({} set)",
        names.join(", ")
    ))
}

/// FNV-1a, 64 bits: a hash that is the same on every machine and in every
/// build (std's hasher promises neither), for assigning shards and
/// recognising outputs. Not a defence against tampering.
pub fn stable_hash(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// [`stable_hash`] as 16 hex digits.
pub fn hash_hex(bytes: &[u8]) -> String {
    format!("{:016x}", stable_hash(bytes))
}

/// One file a shard wrote, with the hash of its bytes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Written {
    /// The frame's index (animations) or the fixture's name (checks).
    pub item: String,
    /// The file, relative to the manifest's folder.
    pub file: String,
    /// [`hash_hex`] of its bytes.
    pub hash: String,
}

/// What a shard did, written beside its outputs as `shard-I-of-N.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// [`FORMAT`].
    pub format: String,
    /// `animation` or `check`.
    pub kind: String,
    /// The vstf version that wrote it.
    pub version: String,
    /// A hash of everything the outputs depend on (the scene and settings
    /// of an animation; the fixtures and golden images of a check).
    pub scene: String,
    /// Which shard.
    pub shard: Shard,
    /// How many items (frames or fixtures) the whole job has.
    pub items: usize,
    /// What this shard wrote, one entry per item it owns.
    pub outputs: Vec<Written>,
}

impl Manifest {
    /// A manifest of this version for `shard` of a job of `kind`.
    pub fn new(kind: &str, scene: String, shard: Shard, items: usize) -> Manifest {
        Manifest {
            format: FORMAT.into(),
            kind: kind.into(),
            version: env!("CARGO_PKG_VERSION").into(),
            scene,
            shard,
            items,
            outputs: Vec::new(),
        }
    }

    /// Records `file` (in `dir`) as the output for `item`.
    pub fn add(&mut self, dir: &Path, item: String, file: &str) -> Result<(), String> {
        let path = dir.join(file);
        let bytes =
            std::fs::read(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        self.outputs.push(Written {
            item,
            file: file.into(),
            hash: hash_hex(&bytes),
        });
        Ok(())
    }

    /// The manifest's file in `dir`.
    pub fn path(dir: &Path, shard: Shard) -> PathBuf {
        dir.join(format!("shard-{}.json", shard.tag()))
    }

    /// Writes the manifest into `dir` (atomically).
    pub fn write(&self, dir: &Path) -> Result<PathBuf, String> {
        let path = Manifest::path(dir, self.shard);
        let text = serde_json::to_string_pretty(self).expect("manifests serialise");
        crate::output::write_atomic(&path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        Ok(path)
    }
}

/// A manifest read back, with the folder its outputs are in.
#[derive(Clone, Debug)]
pub struct Found {
    /// The manifest.
    pub manifest: Manifest,
    /// Its folder.
    pub dir: PathBuf,
}

/// Every shard manifest in the folders `dirs` (each `shard-*.json`).
pub fn read_manifests(dirs: &[PathBuf]) -> Result<Vec<Found>, String> {
    let mut found = Vec::new();
    for dir in dirs {
        let entries =
            std::fs::read_dir(dir).map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
        let mut names: Vec<PathBuf> = entries
            .flatten()
            .map(|e| e.path())
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("shard-") && n.ends_with(".json"))
            })
            .collect();
        names.sort();
        for path in names {
            let text = std::fs::read_to_string(&path)
                .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
            let manifest: Manifest = serde_json::from_str(&text)
                .map_err(|e| format!("{}: not a shard manifest: {e}", path.display()))?;
            found.push(Found {
                manifest,
                dir: dir.clone(),
            });
        }
    }
    Ok(found)
}

/// The manifests of one whole job, in shard order: every shard 1..=N
/// exactly once, all of one kind, format, version, scene and size, every
/// item owned by exactly one shard, and every output's bytes as recorded.
pub fn complete(found: Vec<Found>, kind: &str) -> Result<Vec<Found>, String> {
    let first = found
        .first()
        .ok_or("no shard manifests (shard-I-of-N.json) in the folders given")?;
    let m0 = first.manifest.clone();
    let at = |f: &Found| {
        Manifest::path(&f.dir, f.manifest.shard)
            .display()
            .to_string()
    };
    for f in &found {
        let m = &f.manifest;
        let same = |what: &str, a: &str, b: &str| {
            if a == b {
                Ok(())
            } else {
                Err(format!(
                    "{}: {what} {b:?}, but {} has {a:?}: these shards are not of one job",
                    at(f),
                    at(first)
                ))
            }
        };
        same("format", &m0.format, &m.format)?;
        same("kind", kind, &m.kind)?;
        same("version", &m0.version, &m.version)?;
        same("scene", &m0.scene, &m.scene)?;
        same(
            "shard count",
            &m0.shard.count.to_string(),
            &m.shard.count.to_string(),
        )?;
        same("item count", &m0.items.to_string(), &m.items.to_string())?;
    }
    let mut by_shard: Vec<Option<Found>> = vec![None; m0.shard.count];
    for f in found {
        let slot = &mut by_shard[f.manifest.shard.index - 1];
        if let Some(earlier) = slot {
            return Err(format!(
                "shard {} twice: {} and {}",
                f.manifest.shard,
                at(earlier),
                at(&f)
            ));
        }
        *slot = Some(f);
    }
    let missing: Vec<String> = (1..=m0.shard.count)
        .filter(|i| by_shard[i - 1].is_none())
        .map(|i| i.to_string())
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "missing shard(s) {} of {}: run them, or give the folders they wrote",
            missing.join(", "),
            m0.shard.count
        ));
    }
    let shards: Vec<Found> = by_shard.into_iter().flatten().collect();
    for f in &shards {
        for w in &f.manifest.outputs {
            let path = f.dir.join(&w.file);
            let bytes = std::fs::read(&path)
                .map_err(|e| format!("{}: cannot read {}: {e}", at(f), path.display()))?;
            if hash_hex(&bytes) != w.hash {
                return Err(format!(
                    "{} changed since shard {} wrote it (hash {} against {})",
                    path.display(),
                    f.manifest.shard,
                    hash_hex(&bytes),
                    w.hash
                ));
            }
        }
    }
    Ok(shards)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_env(_: &str) -> Option<String> {
        None
    }

    #[test]
    fn shards_parse_from_the_argument_or_the_array_job() {
        assert_eq!(
            Shard::parse("2/4", no_env).unwrap(),
            Shard { index: 2, count: 4 }
        );
        for bad in ["0/4", "5/4", "1/0", "x/4", "2/", "-1/3"] {
            assert!(Shard::parse(bad, no_env).is_err(), "{bad} accepted");
        }
        let err = Shard::parse("4", no_env).unwrap_err();
        assert!(err.contains("SLURM_ARRAY_TASK_ID"), "{err}");
        let k8s = |v: &str| (v == "JOB_COMPLETION_INDEX").then(|| "0".to_string());
        assert_eq!(Shard::parse("4", k8s).unwrap().index, 1);
        let aws = |v: &str| (v == "AWS_BATCH_JOB_ARRAY_INDEX").then(|| "3".to_string());
        assert_eq!(Shard::parse("4", aws).unwrap().index, 4);
        let aws_beyond = |v: &str| (v == "AWS_BATCH_JOB_ARRAY_INDEX").then(|| "4".to_string());
        assert!(Shard::parse("4", aws_beyond).is_err());
        let slurm = |v: &str| match v {
            "SLURM_ARRAY_TASK_ID" => Some("7".to_string()),
            "SLURM_ARRAY_TASK_MIN" => Some("5".to_string()),
            _ => None,
        };
        assert_eq!(Shard::parse("3", slurm).unwrap().index, 3);
        let slurm_plain = |v: &str| (v == "SLURM_ARRAY_TASK_ID").then(|| "2".to_string());
        assert_eq!(Shard::parse("3", slurm_plain).unwrap().index, 2);
    }

    #[test]
    fn every_item_has_exactly_one_shard() {
        let n = 3;
        let shards: Vec<Shard> = (1..=n).map(|index| Shard { index, count: n }).collect();
        for i in 0..50 {
            assert_eq!(shards.iter().filter(|s| s.owns_frame(i)).count(), 1);
            let name = format!("fixture-{i}");
            assert_eq!(shards.iter().filter(|s| s.owns_fixture(&name)).count(), 1);
        }
        assert!(Shard::WHOLE.owns_fixture("anything") && Shard::WHOLE.owns_frame(7));
        // The hash is FNV-1a's published value, so it cannot drift.
        assert_eq!(stable_hash(b"a"), 0xaf63_dc4c_8601_ec8c);
    }
}
