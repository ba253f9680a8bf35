//! One shard of a sweep run into its own folder, resumably: [`ShardRun::open`] checks the
//! folder (`OUT/shard-K-of-N/`, [`shard_folder`]) against what an earlier run left there (the
//! same sweep and shard, rows that are the shard's and each once; a row cut short by a kill is
//! dropped), writes `shard.json`, and [`ShardRun::evaluate`] computes the points not yet done,
//! appending each finished row to `rows.csv` at once, so a run stopped at any moment resumes
//! where it stopped.

use super::points::{evaluate, Grid};
use super::shard::{
    config_hash, read_rows, rows_header, shard_row, AxisRecord, Shard, ShardRecord,
};
use crate::error::{Error, Result};
use crate::optimize::{Config, Evaluator};
use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// The name of shard `s`'s folder inside a sweep's output folder.
pub fn shard_folder(s: Shard) -> String {
    format!("shard-{}-of-{}", s.k, s.n)
}

/// A shard's folder, opened and checked, with what is left to do.
pub struct ShardRun {
    /// The shard's folder (`OUT/shard-K-of-N`).
    pub dir: PathBuf,
    /// `shard.json` as written when opened (updated by [`ShardRun::evaluate`]).
    pub record: ShardRecord,
    record_path: PathBuf,
    rows_path: PathBuf,
    done: BTreeSet<usize>,
    todo: Vec<usize>,
}

impl ShardRun {
    /// The paths a shard of `out` writes: its folder, `shard.json` and `rows.csv`.
    pub fn paths(out: &Path, shard: Shard) -> [PathBuf; 3] {
        let dir = out.join(shard_folder(shard));
        [dir.clone(), dir.join("shard.json"), dir.join("rows.csv")]
    }

    /// Open shard `shard` of the sweep of `config` (read from `config_file`) over `grid`, in
    /// `out`'s shard folder: refuse a folder that holds another sweep's or shard's work,
    /// take up the rows already there, and write `shard.json`.
    pub fn open(
        config_file: &Path,
        config: &Config,
        grid: &Grid,
        shard: Shard,
        out: &Path,
    ) -> Result<ShardRun> {
        let ext = out
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        if matches!(ext.as_deref(), Some("csv" | "png" | "svg")) {
            return Err(Error::invalid(
                "shard folder",
                format!(
                    "{} is a file name; a sharded sweep writes a folder (its shard in OUT/{})",
                    out.display(),
                    shard_folder(shard)
                ),
            ));
        }
        let [dir, record_path, rows_path] = Self::paths(out, shard);
        crate::io::check_writable(&dir)?;
        let config_bytes = crate::io::read_bytes(config_file)?;
        let mine = shard.indices(grid.len());
        let mut record = ShardRecord {
            format: 1,
            config: config_file.display().to_string(),
            name: config.name.clone(),
            family: config.space.name().to_string(),
            config_hash: config_hash(&config_bytes),
            axes: grid
                .axes
                .iter()
                .map(|x| AxisRecord {
                    key: x.key.clone(),
                    label: x.label(),
                    values: x.values.clone(),
                })
                .collect(),
            grid_size: grid.len(),
            n: shard.n,
            k: shard.k,
            rule: format!("index mod {} == {}", shard.n, shard.k - 1),
            points: mine.len(),
            done: 0,
            complete: false,
            resumed: 0,
            computed: 0,
            indices_done: Vec::new(),
        };
        let shown = dir.display();
        // What an earlier run of this shard left: it must be the same sweep and shard.
        let mut done = BTreeSet::new();
        if record_path.exists() {
            let old: ShardRecord = serde_json::from_slice(&crate::io::read_bytes(&record_path)?)
                .map_err(|e| {
                    Error::invalid("shard folder", format!("{}: {e}", record_path.display()))
                })?;
            if !old.same_sweep(&record) || old.k != record.k {
                return Err(Error::invalid(
                    "shard folder",
                    format!("{shown} holds shard {}/{} of another sweep (config hash {}, axes or shard count differ); choose another folder", old.k, old.n, old.config_hash),
                ));
            }
            if rows_path.exists() {
                let text = String::from_utf8_lossy(&crate::io::read_bytes(&rows_path)?).to_string();
                let (cells, good) = read_rows(&text, grid).map_err(|e| {
                    Error::invalid("shard folder", format!("{}: {e}", rows_path.display()))
                })?;
                for c in cells {
                    if !shard.owns(c.index) || !done.insert(c.index) {
                        return Err(Error::invalid(
                            "shard folder",
                            format!(
                                "{}: grid point {} is not shard {}/{}'s or is there twice",
                                rows_path.display(),
                                c.index,
                                shard.k,
                                shard.n
                            ),
                        ));
                    }
                }
                if good < text.len() {
                    // A line cut short by an interruption: drop it before appending.
                    let f = std::fs::OpenOptions::new()
                        .write(true)
                        .open(&rows_path)
                        .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
                    f.set_len(good as u64)
                        .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
                }
            }
        } else if rows_path.exists() {
            return Err(Error::invalid(
                "shard folder",
                format!(
                    "{} exists without shard.json; choose another folder",
                    rows_path.display()
                ),
            ));
        }
        std::fs::create_dir_all(&dir).map_err(|e| Error::io(shown.to_string(), e))?;
        record.resumed = done.len();
        record.done = done.len();
        record.indices_done = done.iter().copied().collect();
        record.complete = record.done == record.points;
        let todo: Vec<usize> = mine.into_iter().filter(|i| !done.contains(i)).collect();
        let run = ShardRun {
            dir,
            record,
            record_path,
            rows_path,
            done,
            todo,
        };
        run.write_record()?;
        Ok(run)
    }

    /// The grid points left to compute, increasing.
    pub fn todo(&self) -> &[usize] {
        &self.todo
    }

    fn write_record(&self) -> Result<()> {
        let text = serde_json::to_string_pretty(&self.record)
            .map_err(|e| Error::invalid("shard folder", e.to_string()))?;
        crate::io::write_atomic(&self.record_path, (text + "\n").as_bytes())
    }

    /// Compute the points left with `evaluator`, each row appended to `rows.csv` as it
    /// finishes (`tick` after each); raising `stop` ends the run early (a failed write raises
    /// it too, and is the error returned). Writes `shard.json` again and returns it: complete
    /// or not.
    pub fn evaluate(
        mut self,
        config: &Config,
        evaluator: &dyn Evaluator,
        grid: &Grid,
        stop: &AtomicBool,
        tick: &(dyn Fn() + Sync),
    ) -> Result<ShardRecord> {
        let rows_path = &self.rows_path;
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(rows_path)
            .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
        if file
            .metadata()
            .map_err(|e| Error::io(rows_path.display().to_string(), e))?
            .len()
            == 0
        {
            file.write_all(rows_header(grid).as_bytes())
                .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
        }
        let file = Mutex::new(file);
        let failed: Mutex<Option<String>> = Mutex::new(None);
        let cells = evaluate(config, evaluator, grid, &self.todo, Some(stop), &|c| {
            // One write per row: a row is in the file whole or (after a hard kill) cut short
            // at the end, where a resume drops it.
            let row = shard_row(c);
            let mut f = file.lock().unwrap_or_else(|p| p.into_inner());
            if let Err(e) = f.write_all(row.as_bytes()) {
                *failed.lock().unwrap_or_else(|p| p.into_inner()) = Some(e.to_string());
                stop.store(true, Ordering::SeqCst);
            }
            tick();
        });
        if let Some(e) = failed.into_inner().unwrap_or_else(|p| p.into_inner()) {
            return Err(Error::io(rows_path.display().to_string(), e));
        }
        self.done.extend(cells.iter().map(|c| c.index));
        self.record.computed = cells.len();
        self.record.done = self.done.len();
        self.record.indices_done = self.done.iter().copied().collect();
        self.record.complete = self.record.done == self.record.points;
        self.write_record()?;
        Ok(self.record)
    }
}
