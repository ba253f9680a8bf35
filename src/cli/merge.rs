//! `facetlab merge SHARD_DIR... -o DIR`: join the shards of one sweep (`sweep --shard K/N`)
//! into the CSV one unsharded run writes, byte for byte, and its map.
//!
//! The shards must come from one sweep (the same config hash, axes and shard count N), each
//! shard 1..=N once and complete, and together cover every grid point exactly once; otherwise
//! a one-line error names the shard folder (exit code 2) and nothing is written.

use super::optimize::{write_sweep_outputs, Names};
use super::outputs::{refuse_overwrite, Exit};
use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::sweep::{self, ShardRecord, SweepScore};
use std::path::{Path, PathBuf};

/// Flags of `facetlab merge`.
#[derive(Clone, Debug, Args)]
pub struct MergeArgs {
    /// Shard folders written by `facetlab sweep --shard K/N` (each holds shard.json and
    /// rows.csv), or a sweep's folder holding shard-K-of-N/ folders.
    #[arg(required = true, value_name = "SHARD_DIR")]
    pub shards: Vec<PathBuf>,
    /// Output folder (sweep.csv, sweep.png, sweep.svg in it), or a file name whose stem is
    /// used for all three, as for `facetlab sweep --out`.
    #[arg(short = 'o', long = "out", value_name = "FILE|DIR")]
    pub out: PathBuf,
    /// The score drawn on the map and summarised (as for `sweep`).
    #[arg(long, default_value = "brilliance", value_parser = super::flags::sweep_score)]
    pub score: SweepScore,
    /// The two axes the map shows (as for `sweep`).
    #[arg(long, value_name = "KEY1,KEY2")]
    // A String on purpose: two axes of the shards' grid, known only once the shards are read.
    pub map: Option<String>,
    /// Where the map holds an axis it does not show (as for `sweep`).
    #[arg(long, value_name = "KEY=VALUE")]
    pub at: Vec<String>,
    /// A run folder of `facetlab optimize`: draw its path on the map.
    #[arg(long, value_name = "DIR")]
    pub run: Option<PathBuf>,
}

fn read_record(dir: &Path) -> Result<ShardRecord> {
    let path = dir.join("shard.json");
    if !path.is_file() {
        return Err(Error::invalid(
            "SHARD_DIR",
            format!(
                "{}: no shard.json; give folders written by `facetlab sweep --shard K/N`",
                dir.display()
            ),
        ));
    }
    serde_json::from_slice(&facetlab::io::read_bytes(&path)?)
        .map_err(|e| Error::invalid("SHARD_DIR", format!("{}: {e}", path.display())))
}

/// The shard folders: each argument, or the shard-*/ folders inside a sweep folder.
fn shard_dirs(args: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for a in args {
        if a.join("shard.json").is_file() || !a.is_dir() {
            out.push(a.clone());
            continue;
        }
        let mut inner: Vec<PathBuf> = std::fs::read_dir(a)
            .map_err(|e| Error::io(a.display().to_string(), e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with("shard-"))
                    && p.join("shard.json").is_file()
            })
            .collect();
        if inner.is_empty() {
            out.push(a.clone());
        }
        inner.sort();
        out.extend(inner);
    }
    Ok(out)
}

/// Run `facetlab merge`.
pub fn run(a: &MergeArgs) -> Result<Exit> {
    let score = a.score.clone();
    let dirs = shard_dirs(&a.shards)?;
    let records = dirs
        .iter()
        .map(|d| read_record(d))
        .collect::<Result<Vec<_>>>()?;
    let first = &records[0];
    let shown = |i: usize| dirs[i].display().to_string();
    let mut seen: Vec<Option<usize>> = vec![None; first.n];
    for (i, r) in records.iter().enumerate() {
        if !first.same_sweep(r) {
            let why = if r.config_hash != first.config_hash {
                format!(
                    "config hash {} vs {} in {}",
                    r.config_hash,
                    first.config_hash,
                    shown(0)
                )
            } else if r.n != first.n {
                format!("{} shards vs {} in {}", r.n, first.n, shown(0))
            } else {
                format!("other axes than {}", shown(0))
            };
            return Err(Error::invalid(
                "SHARD_DIR",
                format!("{}: shard of another sweep ({why})", shown(i)),
            ));
        }
        if r.k == 0 || r.k > r.n {
            return Err(Error::invalid(
                "SHARD_DIR",
                format!("{}: shard {}/{} is not a shard", shown(i), r.k, r.n),
            ));
        }
        if let Some(j) = seen[r.k - 1] {
            return Err(Error::invalid(
                "SHARD_DIR",
                format!(
                    "{} and {} are both shard {}/{}; give each shard once",
                    shown(j),
                    shown(i),
                    r.k,
                    r.n
                ),
            ));
        }
        seen[r.k - 1] = Some(i);
        if !r.complete || r.done != r.points {
            return Err(Error::invalid(
                "SHARD_DIR",
                format!(
                    "{}: shard {}/{} is incomplete ({} of {} points); run it again to finish",
                    shown(i),
                    r.k,
                    r.n,
                    r.done,
                    r.points
                ),
            ));
        }
    }
    let missing: Vec<String> = seen
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_none())
        .map(|(k, _)| format!("{}/{}", k + 1, first.n))
        .collect();
    if !missing.is_empty() {
        return Err(Error::invalid(
            "SHARD_DIR",
            format!(
                "shard {} of this sweep missing (no folder given for it); {} grid points are not covered",
                missing.join(", "),
                first.grid_size
                    - records.iter().map(|r| r.points).sum::<usize>().min(first.grid_size)
            ),
        ));
    }
    let grid = first.grid();
    let spec = sweep::MapSpec::new(&grid, a.map.as_deref(), &a.at)?;
    let path = match &a.run {
        Some(dir) if spec.axes.len() == 2 => Some(sweep::run_path(
            dir,
            &grid.axes[spec.axes[0]].key,
            &grid.axes[spec.axes[1]].key,
        )?),
        Some(_) => {
            return Err(Error::invalid(
                "--run",
                "draws an optimizer's path on a 2-D map",
            ))
        }
        None => None,
    };
    let (csv, png, svg) = sweep::output_paths(&a.out);
    let mut inputs: Vec<PathBuf> = dirs.clone();
    for d in &dirs {
        inputs.extend([d.join("shard.json"), d.join("rows.csv")]);
    }
    refuse_overwrite(
        &[
            ("-o", a.out.clone()),
            ("-o", csv.clone()),
            ("-o", png.clone()),
            ("-o", svg.clone()),
        ],
        &inputs,
    )?;
    let mut cells = Vec::with_capacity(first.grid_size);
    for (i, r) in records.iter().enumerate() {
        let rows = dirs[i].join("rows.csv");
        let text = String::from_utf8_lossy(&facetlab::io::read_bytes(&rows)?).to_string();
        let (got, _) = sweep::read_rows(&text, &grid)
            .map_err(|e| Error::invalid("SHARD_DIR", format!("{}: {e}", rows.display())))?;
        let shard = sweep::Shard { k: r.k, n: r.n };
        for c in got {
            if !shard.owns(c.index) {
                return Err(Error::invalid(
                    "SHARD_DIR",
                    format!(
                        "{}: grid point {} is not shard {}/{}'s",
                        rows.display(),
                        c.index,
                        r.k,
                        r.n
                    ),
                ));
            }
            cells.push((shown(i), c));
        }
    }
    let cells = sweep::assemble(&grid, cells).map_err(|e| Error::invalid("SHARD_DIR", e))?;
    if let Some(d) = csv.parent() {
        facetlab::io::check_writable(d)?;
    }
    let names = Names {
        name: first.name.clone(),
        family: first.family.clone(),
        file: Path::new(&first.config)
            .file_name()
            .map(|f| f.to_string_lossy().to_string())
            .unwrap_or_default(),
    };
    let labels: Vec<String> = first.axes.iter().map(|x| x.label.clone()).collect();
    println!(
        "merged {} shards: {} grid points of config hash {}",
        first.n, first.grid_size, first.config_hash
    );
    let swept = sweep::Swept {
        grid: &grid,
        cells: &cells,
        labels: &labels,
    };
    write_sweep_outputs(&swept, &score, &spec, &names, path, &a.out)?;
    Ok(Exit::Ok)
}
