//! The house rules of `src/`, checked on the source as it stands: every file at most
//! [`MAX_LINES`] lines of code before its tests, no import circle between the files of one
//! module, and every floor of the library importing only the floors that docs/development.md's
//! Layout table says it may. The table is read from that page itself, so it cannot drift
//! from the code without this test failing. The library names no command-line flag: its
//! errors name settings and fields, and `src/cli` alone turns them into flags.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The most lines a source file may hold before its inline `#[cfg(test)] mod tests { … }`.
const MAX_LINES: usize = 700;

/// The binary's module under `src/` (above every floor; not a row of the table).
const BINARY: &str = "cli";

/// The Python package's native module (feature `python`): a face on top like [`BINARY`], which
/// may import every floor and which no floor may import.
const PYTHON: &str = "python";

type ModPath = Vec<String>;

struct Source {
    path: PathBuf,
    module: ModPath,
    /// The text before the inline test module, comments removed.
    code: String,
    /// Lines before the inline test module.
    lines: usize,
    /// A test-only module (`#[cfg(test)] mod x;` in its parent, or a `tests` folder).
    test_only: bool,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rs_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rs_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// `src/beam/trace.rs` → `[beam, trace]`, `src/beam/mod.rs` → `[beam]`, `src/lib.rs` → `[]`.
fn module_of(rel: &Path) -> ModPath {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_string());
    }
    parts
}

/// Where the inline test module starts (the `#[cfg(test)]` line before `mod tests {`).
fn inline_tests_start(text: &str) -> Option<usize> {
    let lines: Vec<&str> = text.lines().collect();
    (1..lines.len()).find_map(|i| {
        (lines[i - 1].trim() == "#[cfg(test)]" && lines[i].trim_start().starts_with("mod tests {"))
            .then_some(i - 1)
    })
}

/// Remove `//` comments (doc comments included; a `//` inside a string literal cuts the rest of
/// that line, which only ever hides text, never invents an import).
fn strip_comments(text: &str) -> String {
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Modules declared test-only by their parent: `#[cfg(test)]` then `mod name;` or `mod name {`.
fn test_only_children(text: &str) -> BTreeSet<String> {
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    let mut out = BTreeSet::new();
    for i in 1..lines.len() {
        if lines[i - 1].starts_with("#[cfg(test)]") {
            let l = lines[i]
                .trim_start_matches("pub(crate) ")
                .trim_start_matches("pub ");
            if let Some(rest) = l.strip_prefix("mod ") {
                let name: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                out.insert(name);
            }
        }
    }
    out
}

fn load_sources() -> Vec<Source> {
    let src = root().join("src");
    let mut files = Vec::new();
    rs_files(&src, &mut files);
    let mut test_children: BTreeMap<ModPath, BTreeSet<String>> = BTreeMap::new();
    let mut out = Vec::new();
    for path in files {
        let rel = path.strip_prefix(&src).unwrap().to_path_buf();
        // `main.rs` is the binary's root; its `cli` module is read like the library's files
        // (for lengths and circles) but is no floor: it links the library as `facetlab::…`.
        if rel == Path::new("main.rs") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let module = module_of(&rel);
        test_children.insert(module.clone(), test_only_children(&text));
        let head = match inline_tests_start(&text) {
            Some(line) => text.lines().take(line).collect::<Vec<_>>().join("\n"),
            None => text.clone(),
        };
        out.push(Source {
            path: rel,
            lines: head.lines().count(),
            code: strip_comments(&head),
            module,
            test_only: false,
        });
    }
    for s in &mut out {
        s.test_only = (1..=s.module.len()).any(|k| {
            let (parent, name) = (&s.module[..k - 1], &s.module[k - 1]);
            name == "tests"
                || test_children
                    .get(parent)
                    .is_some_and(|set| set.contains(name))
        });
    }
    out
}

fn ident_end(s: &[u8], mut i: usize) -> usize {
    while i < s.len() && (s[i].is_ascii_alphanumeric() || s[i] == b'_') {
        i += 1;
    }
    i
}

/// Every path the code names that starts at `crate`, `super` or `self`, with `use` trees
/// (`a::{b, c::{d}}`) expanded.
fn paths_named(code: &str) -> Vec<Vec<String>> {
    let s = code.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < s.len() {
        let starts_word = i == 0 || !(s[i - 1].is_ascii_alphanumeric() || s[i - 1] == b'_');
        if starts_word
            && [&b"crate::"[..], b"super::", b"self::"]
                .iter()
                .any(|p| s[i..].starts_with(p))
        {
            let (paths, end) = parse_tree(code, i, Vec::new());
            out.extend(paths);
            i = end.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// Parse a path or use tree at byte `i`; returns the full paths and where it ended.
fn parse_tree(code: &str, mut i: usize, prefix: Vec<String>) -> (Vec<Vec<String>>, usize) {
    let s = code.as_bytes();
    let mut path = prefix;
    loop {
        while i < s.len() && s[i].is_ascii_whitespace() {
            i += 1;
        }
        if i < s.len() && s[i] == b'{' {
            let mut out = Vec::new();
            i += 1;
            loop {
                while i < s.len() && (s[i].is_ascii_whitespace() || s[i] == b',') {
                    i += 1;
                }
                if i >= s.len() || s[i] == b'}' {
                    return (out, i + 1);
                }
                let (sub, end) = parse_tree(code, i, path.clone());
                out.extend(sub);
                // skip an `as name`
                i = end;
                while i < s.len() && s[i] != b',' && s[i] != b'}' && s[i] != b';' {
                    i += 1;
                }
            }
        }
        let end = ident_end(s, i);
        if end == i {
            return (vec![path], i);
        }
        path.push(code[i..end].to_string());
        i = end;
        if s[i..].starts_with(b"::") {
            i += 2;
        } else {
            return (vec![path], i);
        }
    }
}

/// The module a path lands in: the longest prefix that is a module of the crate.
fn resolve(from: &[String], path: &[String], modules: &BTreeSet<ModPath>) -> Option<ModPath> {
    let mut base: ModPath = Vec::new();
    let mut rest = path;
    match path.first()?.as_str() {
        "crate" => rest = &path[1..],
        "self" => {
            base = from.to_vec();
            rest = &path[1..];
        }
        "super" => {
            base = from.to_vec();
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
        }
        _ => return None,
    }
    for seg in rest {
        let mut next = base.clone();
        next.push(seg.clone());
        if modules.contains(&next) {
            base = next;
        } else {
            break;
        }
    }
    Some(base)
}

/// Arrows from each non-test file to the modules it names (itself excluded).
fn arrows(sources: &[Source]) -> Vec<(ModPath, ModPath)> {
    let modules: BTreeSet<ModPath> = sources.iter().map(|s| s.module.clone()).collect();
    let mut out = BTreeSet::new();
    for s in sources.iter().filter(|s| !s.test_only) {
        for p in paths_named(&s.code) {
            if let Some(m) = resolve(&s.module, &p, &modules) {
                if m != s.module {
                    out.insert((s.module.clone(), m));
                }
            }
        }
    }
    out.into_iter().collect()
}

/// Strongly connected components with more than one node (Tarjan).
fn cycles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<String, usize>,
        low: BTreeMap<String, usize>,
        stack: Vec<String>,
        out: Vec<Vec<String>>,
    }
    fn visit(t: &mut T, v: &str) {
        let n = t.index.len();
        t.index.insert(v.to_string(), n);
        t.low.insert(v.to_string(), n);
        t.stack.push(v.to_string());
        let next: Vec<String> = t.g.get(v).into_iter().flatten().cloned().collect();
        for w in next {
            if !t.index.contains_key(&w) {
                visit(t, &w);
                let lw = t.low[&w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if t.stack.contains(&w) {
                let iw = t.index[&w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if t.low[v] == t.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                let done = w == v;
                comp.push(w);
                if done {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                t.out.push(comp);
            }
        }
    }
    let mut t = T {
        g: graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        out: Vec::new(),
    };
    for v in graph.keys() {
        if !t.index.contains_key(v) {
            visit(&mut t, v);
        }
    }
    t.out
}

/// docs/development.md's Layout rows for the library's floors: `` | `name` | what it holds | `a`, `b` | ``
/// → name → the floors it may import.
fn readme_floors() -> BTreeMap<String, BTreeSet<String>> {
    let readme = std::fs::read_to_string(root().join("docs/development.md")).unwrap();
    let section = readme
        .split("\n## Layout")
        .nth(1)
        .expect("docs/development.md has a `## Layout` section");
    let section = section.split("\n## ").next().unwrap();
    let mut out = BTreeMap::new();
    for line in section.lines() {
        let cols: Vec<&str> = line.split('|').map(str::trim).collect();
        // | `floor` | holds | may import |  → ["", floor, holds, may, ""]
        if cols.len() != 5 || !cols[1].starts_with('`') || cols[1].contains('/') {
            continue;
        }
        let name = cols[1].trim_matches('`').to_string();
        let may: BTreeSet<String> = cols[3]
            .split(',')
            .map(|x| x.trim().trim_matches('`').to_string())
            .filter(|x| !x.is_empty() && x != "—" && x != "-")
            .collect();
        out.insert(name, may);
    }
    out
}

#[test]
fn every_source_file_is_at_most_700_lines_before_its_tests() {
    let long: Vec<String> = load_sources()
        .iter()
        .filter(|s| s.lines > MAX_LINES)
        .map(|s| format!("src/{} ({} lines)", s.path.display(), s.lines))
        .collect();
    assert!(long.is_empty(), "over {MAX_LINES} lines: {long:?}");
    // The integration tests too.
    let mut files = Vec::new();
    rs_files(&root().join("tests"), &mut files);
    let long: Vec<String> = files
        .iter()
        .filter_map(|p| {
            let text = std::fs::read_to_string(p).unwrap();
            let n = inline_tests_start(&text).unwrap_or(text.lines().count());
            (n > MAX_LINES).then(|| format!("{} ({n} lines)", p.display()))
        })
        .collect();
    assert!(long.is_empty(), "over {MAX_LINES} lines: {long:?}");
}

/// What `find` reports in each `.rs` file of the library (`src/` outside the binary and
/// main.rs; the Python face's files too with `python`), as `path:line: text` items, less
/// those `kept(path, item)`.
fn library_hits(
    find: fn(&str) -> Vec<String>,
    kept: &dyn Fn(&str, &str) -> bool,
    python: bool,
) -> Vec<String> {
    let src = root().join("src");
    let mut files = Vec::new();
    rs_files(&src, &mut files);
    files
        .iter()
        .filter(|p| {
            let rel = p.strip_prefix(&src).unwrap();
            !rel.starts_with(BINARY)
                && rel != Path::new("main.rs")
                && (python || !rel.starts_with(PYTHON))
        })
        .flat_map(|p| {
            let rel = p.strip_prefix(root()).unwrap().display().to_string();
            find(&std::fs::read_to_string(p).unwrap())
                .into_iter()
                .filter(|l| !kept(&rel, l))
                .map(|l| format!("{rel}:{l}"))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Where a quoted flag (`"--` and a letter) stands in `text`, as `line: text` items.
fn flag_literals(text: &str) -> Vec<String> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| {
            l.match_indices("\"--")
                .any(|(i, _)| l[i + 3..].starts_with(|c: char| c.is_ascii_alphabetic()))
        })
        .map(|(i, l)| format!("{}: {}", i + 1, l.trim()))
        .collect()
}

/// The rule: no `"--` followed by a letter anywhere in a `.rs` file of `src/` outside
/// `src/cli` and `src/main.rs`: not in code, not in its tests, not in doc comments or their
/// examples. The library's errors name the setting (`trace depth`, `material`, `config field
/// optimize.method.starts`) and the binary's one table (`FLAGS` in `src/cli/flags.rs`) names
/// the flag; a library test passes a setting's name where a caller would pass a flag. A doc
/// comment may show a command line, written in backticks (`facetlab render --tilt 10@45`),
/// never as a quoted literal; a flag named in the prose of a message (`give --size-mm L`) is
/// not a quoted literal either, and is left to review.
#[test]
fn the_library_quotes_no_command_line_flag() {
    let found = library_hits(flag_literals, &|_, _| false, true);
    assert!(
        found.is_empty(),
        "flag literals in the library (name the setting; src/cli/flags.rs maps it): {found:#?}"
    );
    // The checker sees them, and not a Markdown rule or a `--` alone.
    assert_eq!(flag_literals("x\n  f(\"--depth\", 1);").len(), 1);
    assert!(flag_literals("write!(o, \"---:|\"); \"-- \"").is_empty());
}

#[test]
fn no_import_circle_between_the_files_of_a_module() {
    let sources = load_sources();
    let arrows = arrows(&sources);
    let parents: BTreeSet<ModPath> = sources
        .iter()
        .filter(|s| !s.module.is_empty())
        .map(|s| s.module[..s.module.len() - 1].to_vec())
        .collect();
    let mut found = Vec::new();
    for parent in parents {
        // Each arrow between two descendants of `parent` counts between the children of
        // `parent` that hold them.
        let child = |m: &ModPath| -> Option<String> {
            (m.len() > parent.len() && m[..parent.len()] == parent[..])
                .then(|| m[parent.len()].clone())
        };
        let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in &arrows {
            if let (Some(ca), Some(cb)) = (child(a), child(b)) {
                if ca != cb {
                    g.entry(ca).or_default().insert(cb);
                }
            }
        }
        for c in cycles(&g) {
            found.push(format!("{}: {}", parent.join("::"), c.join(" ↔ ")));
        }
    }
    assert!(found.is_empty(), "import circles: {found:#?}");
}

#[test]
fn each_floor_imports_only_what_the_readme_layout_allows() {
    let floors = readme_floors();
    let sources = load_sources();
    let top: BTreeSet<String> = sources
        .iter()
        .filter(|s| !s.test_only)
        .filter_map(|s| s.module.first().cloned())
        .filter(|m| m != BINARY && m != PYTHON)
        .collect();
    let undocumented: Vec<&String> = top.iter().filter(|m| !floors.contains_key(*m)).collect();
    assert!(
        undocumented.is_empty(),
        "modules with no row in docs/development.md's Layout: {undocumented:?}"
    );
    let stale: Vec<&String> = floors.keys().filter(|f| !top.contains(*f)).collect();
    assert!(stale.is_empty(), "Layout rows with no module: {stale:?}");
    let mut wrong = Vec::new();
    for (a, b) in arrows(&sources) {
        let (Some(fa), Some(fb)) = (a.first(), b.first()) else {
            continue;
        };
        if fb == PYTHON && fa != PYTHON {
            wrong.push(format!(
                "{} → {} (the Python face)",
                a.join("::"),
                b.join("::")
            ));
        } else if fa != fb && fa != BINARY && fa != PYTHON && !floors[fa].contains(fb) {
            wrong.push(format!("{} → {}", a.join("::"), b.join("::")));
        }
    }
    assert!(
        wrong.is_empty(),
        "arrows the Layout does not allow: {wrong:#?}"
    );
    // The allowed arrows themselves run one way.
    let g: BTreeMap<String, BTreeSet<String>> = floors.clone();
    assert!(
        cycles(&g).is_empty(),
        "the Layout's floors import in a circle: {:?}",
        cycles(&g)
    );
}

/// The binary's modules every command may share; each other child of `cli` is a command's.
const SHARED: [&str; 4] = ["flags", "outputs", "progress", "interrupt"];

#[test]
fn serve_imports_no_other_commands_module() {
    // The web page calls the library, as the commands do; it borrows no command's code (what
    // both need belongs in the library, where the Python package gets it too).
    let wrong: Vec<String> = arrows(&load_sources())
        .into_iter()
        .filter(|(a, b)| {
            a.len() >= 2
                && a[..2] == [BINARY, "serve"]
                && b.len() >= 2
                && b[0] == BINARY
                && b[1] != "serve"
                && !SHARED.contains(&b[1].as_str())
        })
        .map(|(a, b)| format!("{} → {}", a.join("::"), b.join("::")))
        .collect();
    assert!(wrong.is_empty(), "serve imports commands: {wrong:#?}");
}

/// Where `--` and a letter stands outside a comment line (`//`, `///`, `//!`) of `text`: in
/// a string, a message's prose, a format string over several lines.
fn flag_words(text: &str) -> Vec<String> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with("//"))
        .filter(|(_, l)| {
            l.match_indices("--")
                .any(|(i, _)| l[i + 2..].starts_with(|c: char| c.is_ascii_alphabetic()))
        })
        .map(|(i, l)| format!("{}: {}", i + 1, l.trim()))
        .collect()
}

/// The library's text outside comments that spells a flag on purpose, by file and words:
/// Slurm's own `--array`, a batch file's format named by the command that writes it (and
/// a batch file's lines in its tests, which hold a user's flags), and the comment `optimize`
/// writes into best.toml for a person (the axis as the command line and the config give it).
const FLAG_WORDS_KEPT: [(&str, &str); 4] = [
    ("src/sweep/shard.rs", "(--array=0-N or 1-N)"),
    ("src/document/batch.rs", "`score --batch`"),
    ("src/document/batch.rs", "gia-reference --set table=0.55"),
    (
        "src/optimize/run.rs",
        "--optic-axis {a}, [score] optic_axis",
    ),
];

/// Stricter than the quoted literal: outside comments the library spells no flag at all,
/// not in the prose of a message or a note either (`give --absorption colour`): it names the
/// setting ([`facetlab::error::setting`]-style `⟨absorption model⟩`) and each face spells it
/// (src/cli/flags.rs for the command line). Doc comments may show command lines.
#[test]
fn the_library_spells_no_flag_outside_comments() {
    let kept = |rel: &str, l: &str| {
        FLAG_WORDS_KEPT
            .iter()
            .any(|(f, w)| rel == *f && l.contains(w))
    };
    let found = library_hits(flag_words, &kept, false);
    assert!(
        found.is_empty(),
        "flags spelled in the library's text (name the setting; each face spells it): {found:#?}"
    );
    assert_eq!(flag_words("  x(\"give --ri N\");\n  /// `--ri`").len(), 1);
}

/// The most the binary's commands (`src/cli/`) may hold of `src/`'s lines, in percent:
/// it parses, calls the library, prints.
const MAX_BINARY_SHARE: f64 = 12.0;

#[test]
fn the_binary_is_at_most_12_percent_of_the_source() {
    let mut files = Vec::new();
    rs_files(&root().join("src"), &mut files);
    let lines = |p: &Path| std::fs::read_to_string(p).unwrap().lines().count();
    let total: usize = files.iter().map(|p| lines(p)).sum();
    let binary: usize = files
        .iter()
        .filter(|p| {
            let rel = p.strip_prefix(root().join("src")).unwrap();
            rel.starts_with(BINARY)
        })
        .map(|p| lines(p))
        .sum();
    let share = 100.0 * binary as f64 / total as f64;
    assert!(
        share <= MAX_BINARY_SHARE,
        "the binary holds {binary} of {total} lines of src/ ({share:.1} %); allowed {MAX_BINARY_SHARE} %: move the work into the library"
    );
}

#[test]
fn only_the_python_face_names_pyo3_and_the_library_builds_without_it() {
    // PyO3 and numpy's crate are the `python` feature's; a floor that named them would not
    // build without Python.
    let named: Vec<String> = load_sources()
        .iter()
        .filter(|s| s.module.first().map(String::as_str) != Some(PYTHON))
        .filter(|s| s.code.contains("pyo3") || s.code.contains("numpy::"))
        .map(|s| format!("src/{}", s.path.display()))
        .collect();
    assert!(named.is_empty(), "outside src/python: {named:?}");
    let lib = std::fs::read_to_string(root().join("src/lib.rs")).unwrap();
    assert!(
        lib.contains("#[cfg(feature = \"python\")]\nmod python;"),
        "src/lib.rs compiles the python module only with the feature"
    );
}

#[test]
fn the_checker_sees_use_trees_and_circles() {
    // The parser and the circle finder on a made-up module: if they missed these, the tests
    // above would pass on anything.
    let paths = paths_named("use crate::a::{b::{C, d}, e as f};\nfn g() { super::h::i(); }");
    let joined: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        joined,
        [
            "crate::a::b::C",
            "crate::a::b::d",
            "crate::a::e",
            "super::h::i"
        ]
    );
    let modules: BTreeSet<ModPath> = [vec!["a".into()], vec!["a".into(), "b".into()]].into();
    let from: ModPath = vec!["x".into(), "y".into()];
    assert_eq!(
        resolve(&from, &paths[0], &modules),
        Some(vec!["a".to_string(), "b".to_string()])
    );
    let g: BTreeMap<String, BTreeSet<String>> = [
        ("p".to_string(), ["q".to_string()].into()),
        ("q".to_string(), ["r".to_string()].into()),
        ("r".to_string(), ["p".to_string()].into()),
        ("s".to_string(), ["p".to_string()].into()),
    ]
    .into();
    assert_eq!(cycles(&g), vec![vec!["p", "q", "r"]]);
    assert!(strip_comments("let x = 1; // crate::a")
        .find("crate")
        .is_none());
}
