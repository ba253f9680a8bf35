//! `facetlab score --batch FILE --jsonl OUT [--shard K/N]`: score many cuts, one per line of
//! FILE, into one JSON line each, resumably.
//!
//! **FILE.** One cut per line: a preset name or a path (.toml, .asc, .gem, .obj, .stl), optionally
//! followed by `--set KEY=VALUE` pairs (`tolkowsky --set crown_angle=34.5 --set table=0.55`).
//! Blank lines and lines starting with `#` are skipped. Lines are numbered from 1 as in the file.
//!
//! **OUT** (JSON Lines, appended). Per cut: `{"line": n, "input": "<the line>", "cut": NAME,
//! …scores}` with the same score keys as `score --json`'s per-cut object, or, when the cut
//! cannot be loaded or scored, `{"line": n, "input": …, "cut": "<first word>", "error": "…"}`.
//! Each line is written with one write as soon as its cut is scored, so an interrupted run
//! keeps every finished cut; running the same command again skips the lines already in OUT (a
//! last line cut short is dropped and redone).
//!
//! **Shards.** With `--shard K/N` (or a Slurm / Kubernetes job array's environment, as for
//! `sweep`), only the cuts whose ordinal `i` (0-based, counting cut lines only) has
//! `i mod N == K − 1` are scored; concatenate the shards' OUT files (or sort by `line`).
//!
//! **Stones.** Each line's stone is chosen as `score` chooses it: a design in its own material
//! unless `--material`/`--ri` chose one, with the colour, size and crystal flags applied
//! (a stone that refuses them, an optic axis for a diamond, is that line's error; a value no
//! stone takes is refused before any line). The notes `score` prints are not said.

use super::cuts::load_with_sets;
use super::optimize::choose_shard;
use super::outputs::{refuse_overwrite, Exit};
use super::score::{settings, ScoreArgs};
use facetlab::document::batch::{cut_lines, BatchOutput};
use facetlab::error::{Error, Result};

/// A line's cut and its `--set` pairs.
pub fn parse_line(line: &str) -> Result<(String, Vec<String>)> {
    let mut words = line.split_whitespace();
    let cut = words.next().unwrap_or_default().to_string();
    let mut sets = Vec::new();
    while let Some(w) = words.next() {
        if w == "--set" {
            match words.next() {
                Some(kv) => sets.push(kv.to_string()),
                None => return Err(Error::invalid("--set", "needs KEY=VALUE after it")),
            }
        } else if let Some(kv) = w.strip_prefix("--set=") {
            sets.push(kv.to_string());
        } else {
            return Err(Error::invalid(
                "batch line",
                format!("`{w}` is not allowed; give CUT [--set KEY=VALUE]..."),
            ));
        }
    }
    Ok((cut, sets))
}

/// Whether `score` was asked for a batch (`--batch`, `--jsonl` or `--shard`): then [`run`]
/// scores it, else [`super::score::run`] scores the CUT arguments.
pub fn asked(a: &ScoreArgs) -> bool {
    a.batch.is_some() || a.jsonl.is_some() || a.shard.is_some()
}

/// Run `facetlab score --batch FILE --jsonl OUT`.
pub fn run(a: &ScoreArgs) -> Result<Exit> {
    run_env(a, &|k| std::env::var(k).ok())
}

/// [`run`] with the environment read through `env`.
pub fn run_env(a: &ScoreArgs, env: &dyn Fn(&str) -> Option<String>) -> Result<Exit> {
    let (Some(batch), Some(out)) = (&a.batch, &a.jsonl) else {
        return Err(Error::invalid(
            if a.batch.is_some() {
                "--batch"
            } else {
                "--jsonl"
            },
            "--batch FILE and --jsonl OUT go together",
        ));
    };
    if !a.cuts.is_empty() {
        return Err(Error::invalid(
            "--batch",
            "the cuts come from the batch file; give no CUT arguments",
        ));
    }
    if a.json.is_some() || a.verify.is_some() {
        return Err(Error::invalid(
            "--batch",
            "writes --jsonl; --json and --verify are for CUT arguments",
        ));
    }
    let s = settings(a)?;
    // The crystal settings no stone takes, refused before OUT is touched.
    s.stone.check(&super::flags::STONE_FIELDS)?;
    refuse_overwrite(&[("--jsonl", out.clone())], std::slice::from_ref(batch))?;
    if out.is_dir() {
        return Err(Error::invalid(
            "--jsonl",
            format!("{} is a folder; give a file name", out.display()),
        ));
    }
    let text = String::from_utf8_lossy(&facetlab::io::read_bytes(batch)?).to_string();
    let lines = cut_lines(&text);
    // The cuts the lines name are inputs too (the output is appended to, never replaced).
    let named: Vec<String> = lines
        .iter()
        .map(|(_, l)| parse_line(l).map(|(c, _)| c).unwrap_or_default())
        .collect();
    refuse_overwrite(
        &[("--jsonl", out.clone())],
        &facetlab::io::guard::cut_files(&named),
    )?;
    let shard = choose_shard(a.shard, env)?;
    let mine: Vec<&(usize, String)> = lines
        .iter()
        .enumerate()
        .filter(|(i, _)| shard.as_ref().is_none_or(|(s, _)| s.owns(*i)))
        .map(|(_, l)| l)
        .collect();
    let mut output = BatchOutput::open(out, batch, &lines)?;
    let skipped = mine
        .iter()
        .filter(|(n, _)| output.done.contains_key(n))
        .count();
    if let Some((sh, from)) = &shard {
        println!(
            "shard {}/{} (from {from}): {} of {} cuts (ordinal mod {} == {})",
            sh.k,
            sh.n,
            mine.len(),
            lines.len(),
            sh.n,
            sh.k - 1
        );
    }
    println!(
        "resumed: {skipped} of {} done (already in {})",
        mine.len(),
        out.display()
    );
    let load = |input: &str| {
        let (name, _) = parse_line(input).unwrap_or_default();
        let cut = parse_line(input).and_then(|(cut, sets)| load_with_sets(&cut, &sets));
        (name, cut)
    };
    let stone = (&s.stone, &super::flags::STONE_FIELDS);
    let count = output.run(&mine, &s.config, stone, &load, &mut |n, e| {
        eprintln!("facetlab: {} line {n}: {e}", batch.display());
    })?;
    let (scored, failed) = (count.scored, count.failed);
    println!(
        "scored {scored}, errors {failed}, skipped {skipped}; wrote {}",
        out.display()
    );
    Ok(Exit::Ok)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_words() {
        assert_eq!(
            parse_line("t --set a=1 --set=b=2").unwrap(),
            ("t".to_string(), vec!["a=1".to_string(), "b=2".to_string()])
        );
        assert!(parse_line("t a=1").is_err());
        assert!(parse_line("t --set").is_err());
    }
}
