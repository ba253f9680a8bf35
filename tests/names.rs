//! The lights the pages and the faces' own texts list by hand are the library's one table
//! (`facetlab::render::lights::table`): README.md, docs/ and the comments and help of src/cli
//! and src/python. A passage (a paragraph of a page, a table row, a run of comment lines, a line
//! of code) that names three or more of the photographs' lights names all of them; one that
//! names six or more laboratory lights names all seven; a `a|b|c` list of three or more lights
//! is the laboratory ones, the photographs' (with `env:FILE`) or both. So a new rig added to the
//! table fails here until every list that spells the rigs out says it too.

use facetlab::render::lights::{table, MAP_FILE};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The files to read: README.md, docs/*.md, and the faces' sources.
fn files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if ["rs", "md", "js", "py", "pyi"]
                .iter()
                .any(|x| p.extension().and_then(|e| e.to_str()) == Some(*x))
            {
                out.push(p);
            }
        }
    }
    let mut out = vec![root().join("README.md")];
    for d in ["docs", "src/cli", "src/python"] {
        walk(&root().join(d), &mut out);
    }
    out.sort();
    out
}

/// The passages of a file, each with its first line's number: a page's paragraphs (a table
/// row, a heading, a line of a code block each alone), a source's runs of comment lines (any
/// other line alone).
fn passages(path: &Path, text: &str) -> Vec<(usize, String)> {
    let md = path.extension().and_then(|e| e.to_str()) == Some("md");
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut cur: Option<(usize, String)> = None;
    let mut fenced = false;
    for (i, line) in text.lines().enumerate() {
        let s = line.trim();
        if md && s.starts_with("```") {
            fenced = !fenced;
        }
        let joins = if md {
            !fenced && !s.is_empty() && !s.starts_with(['|', '#', '`'])
        } else {
            s.starts_with("//") || s.starts_with('#')
        };
        if joins {
            let c = cur.get_or_insert((i + 1, String::new()));
            c.1.push(' ');
            c.1.push_str(s);
            continue;
        }
        out.extend(cur.take());
        out.push((i + 1, line.to_string()));
    }
    out.extend(cur);
    out
}

#[test]
fn every_hand_written_list_of_lights_is_the_table() {
    let t = table();
    let lab: BTreeSet<&'static str> = t.iter().filter(|e| !e.photo).map(|e| e.name).collect();
    let photo: BTreeSet<&'static str> = t.iter().filter(|e| e.photo).map(|e| e.name).collect();
    let all: BTreeSet<&'static str> = lab.union(&photo).copied().collect();
    let mut bad = Vec::new();
    let (mut lab_lists, mut photo_lists) = (0, 0);
    for f in files() {
        let text = std::fs::read_to_string(&f).unwrap();
        let rel = f.strip_prefix(root()).unwrap().display().to_string();
        for (line, p) in passages(&f, &text) {
            let p = p.replace("\\|", "|");
            let words: BTreeSet<&str> = p
                .split(|c: char| !(c.is_ascii_alphanumeric() || c == ':'))
                .collect();
            let named = |set: &BTreeSet<&'static str>| -> BTreeSet<&'static str> {
                set.iter().copied().filter(|n| words.contains(n)).collect()
            };
            let (l, ph) = (named(&lab), named(&photo));
            if l.len() >= 6 {
                lab_lists += 1;
                if l != lab {
                    bad.push(format!(
                        "{rel}:{line}: names {l:?}, not every laboratory light"
                    ));
                }
            }
            if ph.len() >= 3 {
                photo_lists += 1;
                if ph != photo {
                    bad.push(format!(
                        "{rel}:{line}: names {ph:?}, not every photograph's light"
                    ));
                }
            }
            // `a|b|c` lists: runs of names joined by `|`.
            for run in p.split(|c: char| !(c.is_ascii_alphanumeric() || c == ':' || c == '|')) {
                let names: BTreeSet<&str> = run.split('|').filter(|s| !s.is_empty()).collect();
                if names.iter().filter(|n| all.contains(*n)).count() < 3 {
                    continue;
                }
                let with_map = |s: &BTreeSet<&'static str>| -> BTreeSet<&'static str> {
                    let mut s = s.clone();
                    s.insert(MAP_FILE);
                    s
                };
                if names != lab && names != with_map(&photo) && names != with_map(&all) {
                    bad.push(format!("{rel}:{line}: the list {run} is not the table's"));
                }
            }
        }
    }
    // The places known to list them are read (docs/commands.md, docs/serve.md, docs/python.md,
    // src/python/picture.rs …): the test is not passing on nothing.
    assert!(lab_lists >= 3, "{lab_lists} lists of the laboratory lights");
    assert!(
        photo_lists >= 5,
        "{photo_lists} lists of the photographs' lights"
    );
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
