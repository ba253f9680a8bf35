//! The README and the pages under `docs/` run as written: every ```sh block is run by `sh -e` in
//! a folder of its own holding the repository's bundled files (`cuts/`, `optim/`) and an empty
//! `results/`, with `facetlab` on the PATH as this build's binary. A block that cannot run here
//! says why on the line before it, in a comment this test reads:
//! `<!-- readme-test: skip (REASON) -->`, the reason being one of [`REASONS`] (too slow for the
//! tests' debug build, a server, a cluster, the set-up itself). Their links (to headings, to
//! each other, to the repository's files) resolve. (The ```python blocks are run by
//! tests/python/test_docs.py.)
//!
//! The figures the pages quote are marked, `<!--n KEY-->0.775<!--/n-->`, and made by a run:
//! [`SOURCES`] says which command and which JSON key make each. The test checks that every
//! marked figure has a source and that the cheap ones (a score of a preset, …) are what a fresh
//! run gives, to the digits quoted. `FACETLAB_DOCS_UPDATE=1 cargo test --test integration
//! docs_numbers` runs every source (the optimize runs too; `FACETLAB_BIN` may name a release
//! binary to run them faster) and rewrites the marked figures in place, keeping each one's digits.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The reasons a block may give for not running, by their first word.
const REASONS: [&str; 4] = ["slow:", "server:", "cluster:", "the set-up itself"];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every page of docs/, as (path from the root, text).
fn pages() -> Vec<(String, String)> {
    let mut names = vec!["README.md".to_string()];
    let mut docs: Vec<String> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    docs.sort();
    names.extend(docs);
    names
        .into_iter()
        .map(|n| {
            let text = std::fs::read_to_string(root().join(&n)).unwrap();
            (n, text)
        })
        .collect()
}

/// A page's ```sh blocks: (line of the fence, text, the skip reason given before it).
fn sh_blocks(page: &str) -> Vec<(usize, String, Option<String>)> {
    let lines: Vec<&str> = page.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let l = lines[i];
        if l.starts_with("```") {
            let lang = l.trim_start_matches('`').trim();
            let start = i;
            i += 1;
            let mut body = String::new();
            while i < lines.len() && !lines[i].starts_with("```") {
                body += lines[i];
                body.push('\n');
                i += 1;
            }
            if lang == "sh" {
                let skip = start
                    .checked_sub(1)
                    .map(|k| lines[k].trim())
                    .and_then(|p| p.strip_prefix("<!-- readme-test: skip ("))
                    .and_then(|p| p.strip_suffix(") -->"))
                    .map(str::to_string);
                out.push((start + 1, body, skip));
            }
        }
        i += 1;
    }
    out
}

/// GitHub's anchor of a heading.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == '-' || *c == ' ' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a page's headings.
fn anchors(page: &str) -> Vec<String> {
    let mut in_code = false;
    let mut out = Vec::new();
    for l in page.lines() {
        if l.starts_with("```") {
            in_code = !in_code;
        } else if !in_code && l.starts_with('#') {
            out.push(slug(l.trim_start_matches('#')));
        }
    }
    out
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let p = e.path();
        if p.is_dir() {
            copy_dir(&p, &to.join(e.file_name()));
        } else {
            std::fs::copy(&p, to.join(e.file_name())).unwrap();
        }
    }
}

#[test]
fn readme_and_docs_links_resolve() {
    let pages = pages();
    let mut missing = Vec::new();
    for (name, text) in &pages {
        let dir = Path::new(name).parent().unwrap();
        for part in text.split("](").skip(1) {
            let Some(end) = part.find(')') else { continue };
            let target = &part[..end];
            if target.starts_with("http://") || target.starts_with("https://") {
                continue;
            }
            let (file, anchor) = match target.split_once('#') {
                Some((f, a)) => (f, Some(a)),
                None => (target, None),
            };
            let file = if file.is_empty() {
                PathBuf::from(name)
            } else {
                dir.join(file)
            };
            if !root().join(&file).exists() {
                missing.push(format!("{name}: {target} (no file)"));
                continue;
            }
            if let Some(a) = anchor {
                let page = std::fs::read_to_string(root().join(&file)).unwrap();
                if !anchors(&page).iter().any(|h| h == a) {
                    missing.push(format!("{name}: {target} (no heading)"));
                }
            }
        }
    }
    assert!(missing.is_empty(), "links that lead nowhere: {missing:#?}");
    // Every page of docs/ is linked from the README.
    let readme = &pages[0].1;
    for (name, _) in &pages[1..] {
        assert!(
            readme.contains(&format!("]({name}")),
            "the README does not link {name}"
        );
    }
}

#[test]
fn readme_is_short() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let n = readme.lines().count();
    assert!(
        n <= 250,
        "README.md has {n} lines; the reference goes in docs/"
    );
}

#[test]
fn readme_and_docs_sh_blocks_run_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let bin = dir.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_facetlab"), bin.join("facetlab")).unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut ran = 0;
    let mut readme_ran = 0;
    for (name, text) in pages() {
        for (line, body, skip) in sh_blocks(&text) {
            if let Some(reason) = skip {
                assert!(
                    REASONS.iter().any(|r| reason.starts_with(r)),
                    "{name} line {line}: skip reason {reason:?} is not one of {REASONS:?}"
                );
                continue;
            }
            // Each block in a folder of its own, as a reader's fresh clone.
            let work = dir
                .path()
                .join(format!("{}-{line}", name.replace('/', "-")));
            for d in ["cuts", "optim"] {
                copy_dir(&root().join(d), &work.join(d));
            }
            // A clone has `results/` (its README and gallery are not needed here).
            std::fs::create_dir_all(work.join("results")).unwrap();
            let out = Command::new("sh")
                .args(["-e", "-c", &body])
                .current_dir(&work)
                .env("PATH", &path)
                .env("NO_COLOR", "1")
                .output()
                .expect("sh runs");
            assert!(
                out.status.success(),
                "{name}'s sh block at line {line} failed:\n{body}\nstderr: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            // What a block writes goes under results/ (git-ignored), not beside the sources.
            let mut stray: Vec<String> = std::fs::read_dir(&work)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .filter(|n| !["cuts", "optim", "results"].contains(&n.as_str()))
                .collect();
            stray.sort();
            assert!(
                stray.is_empty(),
                "{name}'s sh block at line {line} wrote {stray:?} outside results/"
            );
            ran += 1;
            readme_ran += usize::from(name == "README.md");
        }
    }
    // The README's quick starts (four blocks) and the pages' examples ran.
    assert!(readme_ran >= 4, "ran {readme_ran} of the README's blocks");
    assert!(ran >= 8, "ran {ran} blocks in all");
}

/// How a figure is made: a command (`{out}` is a fresh path for its output) and the JSON file it
/// writes there (`""`: `{out}` itself), and whether the tests run it (cheap) or only the update.
struct Source {
    name: &'static str,
    cheap: bool,
    args: &'static [&'static str],
    json: &'static str,
}

const SOURCES: &[Source] = &[
    Source {
        name: "gia",
        cheap: true,
        args: &["score", "gia-reference", "--json", "{out}"],
        json: "",
    },
    Source {
        name: "quartz",
        cheap: true,
        args: &["score", "optim/quartz-brilliant.asc", "--json", "{out}"],
        json: "",
    },
    Source {
        name: "quartz-split",
        cheap: true,
        args: &["score", "optim/quartz-split.asc", "--json", "{out}"],
        json: "",
    },
    Source {
        name: "quartz-split-tied",
        cheap: true,
        args: &[
            "score",
            "optim/quartz-split.asc",
            "--set",
            "P1+P1b=-1",
            "--json",
            "{out}",
        ],
        json: "",
    },
    Source {
        name: "main",
        cheap: false,
        args: &[
            "optimize",
            "optim/round-brilliance.toml",
            "--quiet",
            "--out",
            "{out}",
        ],
        json: "report.json",
    },
    Source {
        name: "design-quartz",
        cheap: false,
        args: &[
            "optimize",
            "optim/design-quartz.toml",
            "--quiet",
            "--out",
            "{out}",
        ],
        json: "report.json",
    },
    Source {
        name: "design-tied",
        cheap: false,
        args: &[
            "optimize",
            "optim/design-tied.toml",
            "--quiet",
            "--out",
            "{out}",
        ],
        json: "report.json",
    },
];

/// The figures: KEY → (source, JSON pointer in its document, factor).
const FIGURES: &[(&str, &str, &str, f64)] = &[
    ("main.table", "main", "/winners/0/params/table", 100.0),
    ("main.crown", "main", "/winners/0/params/crown_angle", 1.0),
    (
        "main.pavilion",
        "main",
        "/winners/0/params/pavilion_angle",
        1.0,
    ),
    (
        "main.brilliance",
        "main",
        "/winners/0/scores/brilliance",
        1.0,
    ),
    ("main.fire", "main", "/winners/0/scores/fire", 1.0),
    (
        "main.start.brilliance",
        "main",
        "/start/scores/brilliance",
        1.0,
    ),
    ("main.start.fire", "main", "/start/scores/fire", 1.0),
    ("main.evaluations", "main", "/search/evaluations", 1.0),
    (
        "design-quartz.start",
        "design-quartz",
        "/start/scores/brilliance",
        1.0,
    ),
    (
        "design-quartz.best",
        "design-quartz",
        "/winners/0/scores/brilliance",
        1.0,
    ),
    (
        "design-quartz.evaluations",
        "design-quartz",
        "/search/evaluations",
        1.0,
    ),
    (
        "design-tied.start",
        "design-tied",
        "/start/scores/brilliance",
        1.0,
    ),
    (
        "design-tied.best",
        "design-tied",
        "/winners/0/scores/brilliance",
        1.0,
    ),
    (
        "design-tied.evaluations",
        "design-tied",
        "/search/evaluations",
        1.0,
    ),
    ("design-tied.P1", "design-tied", "/winners/0/params/P1", 1.0),
    (
        "design-tied.tie",
        "design-tied",
        "/winners/0/params/P1+P1b",
        1.0,
    ),
];

/// The score keys a `score --json` source gives as `SOURCE.KEY` (`gia.aset.blue`).
fn figure(key: &str) -> Option<(&'static str, String, f64)> {
    if let Some(&(_, s, p, f)) = FIGURES.iter().find(|(k, ..)| *k == key) {
        return Some((s, p.to_string(), f));
    }
    let (src, rest) = key.split_once('.')?;
    let s = SOURCES
        .iter()
        .find(|s| s.name == src && s.args[0] == "score")?;
    Some((s.name, format!("/{}", rest.replace('.', "/")), 1.0))
}

/// Every marked figure of a page: (byte range of the value, key, value as written).
fn marked(text: &str) -> Vec<(std::ops::Range<usize>, String, String)> {
    let mut out = Vec::new();
    let mut at = 0;
    while let Some(i) = text[at..].find("<!--n ") {
        let open = at + i;
        let close = open + text[open..].find("-->").expect("a marker ends");
        let key = text[open + 6..close].trim().to_string();
        let start = close + 3;
        let end = start
            + text[start..]
                .find("<!--/n-->")
                .expect("a marked figure ends");
        out.push((start..end, key, text[start..end].to_string()));
        at = end;
    }
    out
}

/// `value` written with as many decimals as `like` has.
fn same_digits(value: f64, like: &str) -> String {
    let decimals = like.split_once('.').map_or(0, |(_, d)| d.len());
    format!("{value:.decimals$}")
}

fn run_source(s: &Source, dir: &Path) -> serde_json::Value {
    let out = dir.join(s.name);
    let bin = std::env::var("FACETLAB_BIN").unwrap_or(env!("CARGO_BIN_EXE_facetlab").into());
    let args: Vec<String> = s
        .args
        .iter()
        .map(|a| a.replace("{out}", &out.to_string_lossy()))
        .collect();
    let done = Command::new(bin)
        .args(&args)
        .current_dir(root())
        .output()
        .expect("facetlab runs");
    assert!(
        done.status.success(),
        "{}: facetlab {args:?} failed: {}",
        s.name,
        String::from_utf8_lossy(&done.stderr)
    );
    let file = if s.json.is_empty() {
        out
    } else {
        out.join(s.json)
    };
    serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap()
}

#[test]
fn docs_numbers_are_made_by_a_run() {
    let update = std::env::var_os("FACETLAB_DOCS_UPDATE").is_some();
    let pages = pages();
    let mut unknown = Vec::new();
    let mut needed = BTreeMap::new();
    for (name, text) in &pages {
        for (_, key, _) in marked(text) {
            match figure(&key) {
                Some((src, ..)) => {
                    needed.insert(src, ());
                }
                None => unknown.push(format!("{name}: {key}")),
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "marked figures with no source in tests/readme.rs: {unknown:?}"
    );
    let dir = tempfile::tempdir().unwrap();
    let mut docs = BTreeMap::new();
    for s in SOURCES {
        if needed.contains_key(s.name) && (s.cheap || update) {
            docs.insert(s.name, run_source(s, dir.path()));
        }
    }
    let mut wrong = Vec::new();
    for (name, text) in &pages {
        let mut new = text.clone();
        // From the end, so the earlier ranges stay put.
        for (range, key, written) in marked(text).into_iter().rev() {
            let (src, pointer, factor) = figure(&key).unwrap();
            let Some(doc) = docs.get(src) else { continue };
            let value = doc
                .pointer(&pointer)
                .and_then(serde_json::Value::as_f64)
                .unwrap_or_else(|| panic!("{name}: {key}: {src} has no number at {pointer}"));
            let fresh = same_digits(value * factor, &written);
            if fresh != written {
                wrong.push(format!("{name}: {key} says {written}, a run gives {fresh}"));
                new.replace_range(range, &fresh);
            }
        }
        if update && &new != text {
            std::fs::write(root().join(name), new).unwrap();
        }
    }
    assert!(
        update || wrong.is_empty(),
        "figures that a fresh run does not give (rewrite them with \
         `FACETLAB_DOCS_UPDATE=1 cargo test --test integration docs_numbers`): {wrong:#?}"
    );
}
