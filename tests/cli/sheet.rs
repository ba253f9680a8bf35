//! `facetlab sheet`: the cutting sheet's numbers are `info`'s, its rows the tiers in cutting
//! order, its SVG well-formed, its PDF one A4 page; the cutting mode has one screen per tier
//! with the stone growing; bad input is refused in one line.

use super::{bad, files, ok};
use serde_json::Value;
use std::path::Path;

/// A small brilliant on a 96 gear with the designer's instructions on three lines.
const MINI: &str = "GemCad 5.0
g 96 0.0
y 8 y
I 1.54
H Mini
H by a tester
a -90.000000 1.000000 3 n G 9 15 21 27 33 39 45 51 57 63 69 75 81 87 93
a -41.000000 0.691553 96 n P 12 24 36 48 60 72 84 G Cut to TCP
a 0.000000 -0.900000 96 n K G Small culet
a 34.000000 0.595019 96 n B 12 24 36 48 60 72 84 G Leave some girdle
a 0.000000 0.332598 96 n T
";

fn read(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap()
}

/// The text of the element with `id` in a parsed SVG.
fn text_of(doc: &roxmltree::Document, id: &str) -> String {
    doc.descendants()
        .find(|n| n.attribute("id") == Some(id))
        .unwrap_or_else(|| panic!("no #{id}"))
        .text()
        .unwrap()
        .to_string()
}

/// The number after `label` in `line` (`L/W 1.000`).
fn number_after(line: &str, label: &str) -> f64 {
    let rest = &line[line
        .find(label)
        .unwrap_or_else(|| panic!("{label} not in {line}"))
        + label.len()..];
    let t: String = rest
        .trim_start()
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    t.parse()
        .unwrap_or_else(|_| panic!("no number after {label} in {line}"))
}

/// (section, name, angle, facets) of each row.
fn rows(doc: &roxmltree::Document) -> Vec<(String, String, f64, usize)> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some("step"))
        .map(|n| {
            (
                n.attribute("data-section").unwrap().to_string(),
                n.attribute("data-name").unwrap().to_string(),
                n.attribute("data-angle").unwrap().parse().unwrap(),
                n.attribute("data-facets").unwrap().parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn the_sheets_numbers_are_infos_and_its_rows_the_tiers_in_cutting_order() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    std::fs::write(dir.join("mini.asc"), MINI).unwrap();
    for (cut, size) in [
        ("tolkowsky", ["--diameter-mm", "7"]),
        ("mini.asc", ["--size-mm", "8"]),
    ] {
        let info: Value =
            serde_json::from_str(&ok(dir, &["info", cut, size[0], size[1], "--json"])).unwrap();
        ok(
            dir,
            &["sheet", cut, size[0], size[1], "-o", "s.svg", "--force"],
        );
        let svg = read(dir, "s.svg");
        let doc = roxmltree::Document::parse(&svg).expect("the sheet is well-formed XML");
        let root = doc.root_element();
        assert_eq!(
            (root.attribute("width"), root.attribute("height")),
            (Some("210mm"), Some("297mm"))
        );
        let ratios = text_of(&doc, "ratios");
        for (label, key) in [
            ("L/W", "l_w"),
            ("T/W", "t_w"),
            ("P/W", "p_w"),
            ("C/W", "c_w"),
            ("H/W", "h_w"),
            ("Vol/W³", "vol_w3"),
        ] {
            let want = info["ratios"][key].as_f64().unwrap();
            let got = number_after(&ratios, label);
            assert!(
                (got - want).abs() <= 5.1e-4,
                "{cut} {label}: sheet {got}, info {want}"
            );
        }
        let size_line = text_of(&doc, "size");
        let carats = number_after(&size_line, "weight");
        let want = info["carats"].as_f64().unwrap();
        assert!(
            (carats - want).abs() <= 5.1e-4,
            "{cut}: {carats} ct, info {want}"
        );
        assert!(
            size_line.contains(info["material"].as_str().unwrap()),
            "{size_line}"
        );
        let w = info["size_mm"]["width"].as_f64().unwrap();
        assert!(size_line.contains(&format!("{w:.2}")), "{size_line}");
        let design = text_of(&doc, "design");
        let facets = info["facet_count"].as_u64().unwrap() as usize;
        assert!(design.contains(&format!("= {facets};")), "{design}");

        // Rows: every facet once, in cutting order, the table last.
        let rows = rows(&doc);
        assert_eq!(rows.iter().map(|r| r.3).sum::<usize>(), facets, "{rows:?}");
        let rank = |s: &str| {
            ["preform", "pavilion", "girdle", "crown", "table"]
                .iter()
                .position(|x| *x == s)
                .unwrap()
        };
        assert!(
            rows.windows(2).all(|w| rank(&w[0].0) <= rank(&w[1].0)),
            "{rows:?}"
        );
        assert_eq!(rows.last().unwrap().0, "table");
        assert_eq!(rows[0].0, "preform");
        if cut == "mini.asc" {
            let got: Vec<(&str, &str, f64, usize)> = rows
                .iter()
                .map(|r| (r.0.as_str(), r.1.as_str(), r.2, r.3))
                .collect();
            assert_eq!(
                got,
                [
                    ("preform", "P", 41.0, 8),
                    ("preform", "G", 90.0, 16),
                    ("pavilion", "K", 0.0, 1),
                    ("crown", "B", 34.0, 8),
                    ("table", "T", 0.0, 1),
                ]
            );
            assert!(svg.contains("Cut to TCP") && svg.contains("Leave some girdle"));
            assert!(
                svg.contains("Angles for R.I. = 1.540"),
                "the design's index"
            );
            assert!(svg.contains("by a tester"), "the author line");
        } else {
            // The round's tiers at the preset's angles, the pavilion mains first.
            assert_eq!((rows[0].1.as_str(), rows[0].2, rows[0].3), ("P1", 40.75, 8));
            assert!(rows.iter().any(|r| r.2 == 34.5 && r.3 == 8), "{rows:?}");
            assert!(svg.contains("at 7 mm"), "depths in mm at the size");
        }
        // Every crown and pavilion facet is named in the face-up and face-down views (the
        // girdle's, upright, only where the side view shows them): at least one label each.
        let girdle = number_after(&design, "+") as usize;
        let labels = doc
            .descendants()
            .filter(|n| n.attribute("class") == Some("facet"))
            .count();
        assert!(
            labels >= facets - girdle,
            "{labels} labels for {facets} facets, {girdle} on the girdle"
        );
    }
    // The HTML holds the same page.
    ok(dir, &["sheet", "tolkowsky", "-o", "s.html"]);
    let html = read(dir, "s.html");
    let (a, b) = (html.find("<svg").unwrap(), html.rfind("</svg>").unwrap());
    roxmltree::Document::parse(&html[a..b + 6]).expect("the page's SVG is well-formed");
    assert!(html.contains("@page { size: A4; margin: 0 }"));
}

#[test]
fn the_pdf_is_one_a4_page() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    ok(
        dir,
        &["sheet", "emerald", "--diameter-mm", "6", "-o", "e.pdf"],
    );
    let pdf = std::fs::read(dir.join("e.pdf")).unwrap();
    assert!(pdf.starts_with(b"%PDF-"));
    let text = String::from_utf8_lossy(&pdf);
    let pages = text.matches("/Type /Page").count() - text.matches("/Type /Pages").count();
    assert_eq!(pages, 1, "one page");
    assert!(text.contains("/Count 1"), "the page tree holds one page");
    assert!(
        text.contains("/MediaBox [0 0 595.28 841.89]"),
        "A4 in points"
    );
    assert!(text.contains("%%EOF"));
}

#[test]
fn the_cutting_mode_has_one_screen_per_tier_and_the_stone_grows() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    ok(dir, &["sheet", "princess", "-o", "p.svg"]);
    let svg = read(dir, "p.svg");
    let sheet = rows(&roxmltree::Document::parse(&svg).unwrap());
    ok(dir, &["sheet", "princess", "--mode", "-o", "p.html"]);
    let html = read(dir, "p.html");
    let mut grown: Vec<usize> = Vec::new();
    for part in html.split("<section class=\"step\"").skip(1) {
        let at = part.find("data-facets=\"").unwrap() + 13;
        grown.push(
            part[at..at + part[at..].find('"').unwrap()]
                .parse()
                .unwrap(),
        );
        let (a, b) = (part.find("<svg").unwrap(), part.find("</svg>").unwrap());
        roxmltree::Document::parse(&part[a..b + 6]).expect("each screen's SVG is well-formed");
    }
    assert_eq!(grown.len(), sheet.len(), "one screen per row of the sheet");
    assert!(grown.windows(2).all(|w| w[1] > w[0]), "{grown:?}");
    let mut sum = 0;
    for (g, r) in grown.iter().zip(&sheet) {
        sum += r.3;
        assert_eq!(*g, sum, "each screen adds its tier's facets");
    }
    assert!(html.contains("ArrowRight") && html.contains("id=\"next\""));
}

#[test]
fn bad_sheet_input_is_refused_in_one_line_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    std::fs::write(dir.join("mini.asc"), MINI).unwrap();
    let before = files(dir);
    bad(
        dir,
        &["sheet", "tolkowsky", "-o", "s.png"],
        &["-o", ".html, .svg, .pdf"],
    );
    bad(
        dir,
        &["sheet", "tolkowsky", "--mode", "-o", "s.pdf"],
        &["--mode", ".html"],
    );
    bad(
        dir,
        &["sheet", "tolkowsky", "--diameter-mm", "-2", "-o", "s.svg"],
        &["--diameter-mm"],
    );
    bad(
        dir,
        &["sheet", "nosuch.asc", "-o", "s.svg"],
        &["nosuch.asc"],
    );
    bad(dir, &["sheet", "mini.asc", "-o", "mini.asc"], &["mini.asc"]);
    assert_eq!(files(dir), before, "nothing written");
    assert_eq!(read(dir, "mini.asc"), MINI, "the input is untouched");
    ok(dir, &["sheet", "tolkowsky", "-o", "s.svg"]);
    bad(
        dir,
        &["sheet", "tolkowsky", "-o", "s.svg"],
        &["s.svg", "--force"],
    );
}
