//! The README runs as written: every ```sh block is run by `sh -e` in a folder of its own holding
//! the repository's bundled files (`cuts/`, `optim/`), with `facetlab` on the PATH as this build's
//! binary. A block that cannot run here says why on the line before it, in a comment this test
//! reads: `<!-- readme-test: skip (REASON) -->`, the reason being one of [`REASONS`] (too slow for
//! the tests' debug build, a server, a cluster, the set-up itself). Its links to its own headings
//! and the files it names exist.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The reasons a block may give for not running, by their first word.
const REASONS: [&str; 4] = ["slow:", "server:", "cluster:", "the set-up itself"];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The README's ```sh blocks: (line of the fence, text, the skip reason given before it).
fn sh_blocks(readme: &str) -> Vec<(usize, String, Option<String>)> {
    let lines: Vec<&str> = readme.lines().collect();
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
fn readme_links_to_its_own_headings() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let mut in_code = false;
    let mut anchors = Vec::new();
    for l in readme.lines() {
        if l.starts_with("```") {
            in_code = !in_code;
        } else if !in_code && l.starts_with('#') {
            anchors.push(slug(l.trim_start_matches('#')));
        }
    }
    let mut missing = Vec::new();
    for part in readme.split("](#").skip(1) {
        let a = &part[..part.find(')').unwrap()];
        if !anchors.iter().any(|h| h == a) {
            missing.push(a.to_string());
        }
    }
    assert!(missing.is_empty(), "links to no heading: {missing:?}");
}

#[test]
fn readme_sh_blocks_run_as_written() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let blocks = sh_blocks(&readme);
    assert!(blocks.len() >= 8, "found only {} sh blocks", blocks.len());
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
    for (line, body, skip) in &blocks {
        if let Some(reason) = skip {
            assert!(
                REASONS.iter().any(|r| reason.starts_with(r)),
                "README line {line}: skip reason {reason:?} is not one of {REASONS:?}"
            );
            continue;
        }
        // Each block in a folder of its own, as a reader's fresh clone.
        let work = dir.path().join(format!("line-{line}"));
        for d in ["cuts", "optim"] {
            copy_dir(&root().join(d), &work.join(d));
        }
        // A clone has `results/` (its README and gallery are not needed here).
        std::fs::create_dir_all(work.join("results")).unwrap();
        let out = Command::new("sh")
            .args(["-e", "-c", body])
            .current_dir(&work)
            .env("PATH", &path)
            .env("NO_COLOR", "1")
            .output()
            .expect("sh runs");
        assert!(
            out.status.success(),
            "README's sh block at line {line} failed:\n{body}\nstderr: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        ran += 1;
    }
    // The quick starts and the command overview at least (six blocks) ran.
    assert!(ran >= 6, "ran {ran} of {} blocks", blocks.len());
}
