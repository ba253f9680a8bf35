//! `facetlab score --batch FILE --jsonl OUT`: the cut lines of a batch file, and OUT's JSON
//! Lines (their shape is [`score`](super::score)'s [`batch_line`] and [`batch_error_line`])
//! written resumably: [`BatchOutput::open`] reads what OUT already holds, checks it is this
//! batch's, drops a last line cut short, and appends; [`BatchOutput::run`] scores the lines
//! not yet done, one write per line.
//!
//! Errors name the setting `batch output` (the binary names its flag).

use super::score::{batch_error_line, batch_line};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::metrics::{score, ColourNotes, ScoreConfig, StoneChoice, StoneFields};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The setting the errors about the output name.
const OUTPUT: &str = "batch output";

/// The cut lines of a batch file: `(line number, text)`, numbered from 1 as in the file;
/// blank lines and lines starting with `#` are skipped.
pub fn cut_lines(text: &str) -> Vec<(usize, String)> {
    text.lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim().to_string()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
        .collect()
}

/// What a batch's output already holds: the lines done (`line` → `input`), the byte length of
/// its complete lines, and the file's length.
fn done_lines(path: &Path) -> Result<(BTreeMap<usize, String>, usize, usize)> {
    let mut done = BTreeMap::new();
    if !path.exists() {
        return Ok((done, 0, 0));
    }
    let bytes = crate::io::read_bytes(path)?;
    let text = String::from_utf8_lossy(&bytes);
    let mut good = 0;
    for (n, line) in text.split_inclusive('\n').enumerate() {
        let Some(body) = line.strip_suffix('\n') else {
            break; // cut short by an interruption: redone
        };
        let v: serde_json::Value = serde_json::from_str(body).map_err(|_| {
            Error::invalid(
                OUTPUT,
                format!(
                    // The file's format, named by the command that writes it (kept).
                    "{} line {} is not a line of `score --batch`; write to a new file",
                    path.display(),
                    n + 1
                ),
            )
        })?;
        let (Some(l), Some(input)) = (v["line"].as_u64(), v["input"].as_str()) else {
            return Err(Error::invalid(
                OUTPUT,
                format!(
                    "{} line {} has no `line` and `input`; write to a new file",
                    path.display(),
                    n + 1
                ),
            ));
        };
        done.insert(l as usize, input.to_string());
        good += line.len();
    }
    Ok((done, good, bytes.len()))
}

/// A batch's JSON Lines output, open for appending after the lines it already holds.
pub struct BatchOutput {
    path: PathBuf,
    file: File,
    /// The lines already written: line number → the batch file's text of it.
    pub done: BTreeMap<usize, String>,
}

/// What [`BatchOutput::run`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BatchCount {
    /// Cuts scored.
    pub scored: usize,
    /// Lines whose cut could not be loaded (each written as an error line).
    pub failed: usize,
    /// Lines already in the output, not scored again.
    pub skipped: usize,
}

impl BatchOutput {
    /// Open `out` for the batch file `batch` whose cut lines are `lines`: refused when it
    /// holds a line that is not that line of the batch (or is not a batch's output at all);
    /// a last line cut short is dropped, to be redone.
    pub fn open(out: &Path, batch: &Path, lines: &[(usize, String)]) -> Result<BatchOutput> {
        if let Some(m) = crate::io::guard::not_regular(out) {
            return Err(Error::invalid(OUTPUT, format!("{} {m}", out.display())));
        }
        let (done, good, len) = done_lines(out)?;
        for (n, input) in &done {
            match lines.iter().find(|(l, _)| l == n) {
                Some((_, now)) if now == input => {}
                _ => {
                    return Err(Error::invalid(
                        OUTPUT,
                        format!(
                            "{} holds line {n} `{input}`, which is not that line of {}; write to a new file",
                            out.display(),
                            batch.display()
                        ),
                    ))
                }
            }
        }
        let dir = out
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        crate::io::check_writable(dir)?;
        let io = |e: std::io::Error| Error::io(out.display().to_string(), e);
        if good < len {
            let f = std::fs::OpenOptions::new()
                .write(true)
                .open(out)
                .map_err(io)?;
            f.set_len(good as u64).map_err(io)?;
        }
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(out)
            .map_err(io)?;
        Ok(BatchOutput {
            path: out.to_path_buf(),
            file,
            done,
        })
    }

    /// Score the lines of `mine` not done yet under `cfg`, each cut's stone chosen by `stone`
    /// as `score` chooses it (a design in its own material unless one was chosen, the colour,
    /// size and crystal settings applied; the notes unsaid), appending one JSON line each as
    /// soon as it is scored. `load` reads a line into the name an error line gives its cut
    /// and the cut, or the error written for it (which `failed` also hears), as is a stone
    /// that refuses the settings (an optic axis for a diamond). The settings no stone takes
    /// are refused before any line ([`StoneChoice::check`]).
    pub fn run(
        &mut self,
        mine: &[&(usize, String)],
        cfg: &ScoreConfig,
        stone: (&StoneChoice, &StoneFields<'_>),
        load: &dyn Fn(&str) -> (String, Result<Cut>),
        failed: &mut dyn FnMut(usize, &Error),
    ) -> Result<BatchCount> {
        let (choice, fields) = stone;
        choice.check(fields)?;
        let scored = |cut: &Cut| -> Result<crate::metrics::Scores> {
            let stones = choice.stones(
                std::slice::from_ref(cut),
                fields,
                ColourNotes::Traced,
                &mut |_, _| {},
            )?;
            let (cfg, _) = stones.configs(cfg, |c, material| ScoreConfig {
                material,
                ..c.clone()
            });
            Ok(score(&cut.solid, &cfg))
        };
        let mut count = BatchCount {
            skipped: mine
                .iter()
                .filter(|(n, _)| self.done.contains_key(n))
                .count(),
            ..BatchCount::default()
        };
        for (n, input) in mine {
            if self.done.contains_key(n) {
                continue;
            }
            let (name, cut) = load(input);
            let json = match cut.and_then(|cut| Ok((scored(&cut)?, cut))) {
                Ok((sc, cut)) => {
                    count.scored += 1;
                    batch_line(*n, input, &cut.name, &sc)
                }
                Err(e) => {
                    count.failed += 1;
                    failed(*n, &e);
                    batch_error_line(*n, input, &name, &e.to_string())
                }
            }
            .map_err(|e| Error::invalid(OUTPUT, e.to_string()))?;
            self.file
                .write_all((json + "\n").as_bytes())
                .map_err(|e| Error::io(self.path.display().to_string(), e))?;
        }
        Ok(count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_numbered_as_in_the_file() {
        let l = cut_lines("# head\n\ntolkowsky\n  gia-reference --set table=0.55 \n");
        assert_eq!(
            l,
            vec![
                (3, "tolkowsky".to_string()),
                (4, "gia-reference --set table=0.55".to_string())
            ]
        );
    }
}
