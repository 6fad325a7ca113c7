//! `vstf merge`: the outputs of sharded runs assembled, once every shard
//! is there: an animation's frames into its folder, GIF or APNG; a check
//! suite's results into the table, the JSON and the report an unsharded
//! run gives (and its verdict).

use super::args::MergeArgs;
use super::check::{conclude, Asked};
use std::time::Instant;
use vstf::error::Error;

/// Merges the shards found in `args.dirs`, by the kind their manifests
/// name.
pub fn run(args: MergeArgs) -> Result<(), Error> {
    let started = Instant::now();
    let found = vstf::shard::read_manifests(&vstf::check::sharded::with_shard_folders(&args.dirs))?;
    let kind = found
        .first()
        .map(|f| f.manifest.kind.clone())
        .ok_or("no shard manifests (shard-I-of-N.json) in the folders given")?;
    match kind.as_str() {
        "animation" => {
            let out = args.out.ok_or_else(|| {
                format!(
                    "merging an animation needs --out: {}",
                    vstf::animate::ANIMATION_OUTPUTS
                )
            })?;
            let output = vstf::animate::Output::from_path(&out)?;
            output.preflight(true)?;
            let shards = found.first().map_or(0, |f| f.manifest.shard.count);
            let n = vstf::animate::merge(found, &output, args.fps)?;
            eprintln!(
                "merged {n} frames from {shards} shards -> {}",
                out.display()
            );
            Ok(())
        }
        "check" => {
            if args.out.is_some() {
                return Err(Error::usage(
                    "--out is for animations; a check suite takes --json and --report",
                ));
            }
            let reports = vstf::check::sharded::merge(found)?;
            let asked = Asked {
                json: args.json,
                report: args.report,
                verbose: args.verbose,
                files: Vec::new(),
            };
            conclude(
                &reports,
                &asked,
                Some(std::path::Path::new("the shards' folders")),
                started,
            )
        }
        other => Err(Error::Other(format!(
            "shard manifests of an unknown kind {other:?}"
        ))),
    }
}
