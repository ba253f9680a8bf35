//! Faceters' workflow: `facetlab materials [--json]` and `--material ri:N[:BG]`.

use super::{bad, ok};
use tempfile::tempdir;

#[test]
fn materials_json_lists_every_stone_with_its_formula_and_source() {
    let d = tempdir().unwrap();
    let j: serde_json::Value =
        serde_json::from_str(&ok(d.path(), &["materials", "--json"])).unwrap();
    let rows = j.as_array().unwrap();
    assert!(rows.len() >= 17, "{}", rows.len());
    for r in rows {
        for k in [
            "name",
            "nd",
            "dispersion",
            "formula",
            "source",
            "ordinary_ray",
            "density",
        ] {
            assert!(r.get(k).is_some(), "{k} missing in {r}");
        }
        assert!(r["nd"].as_f64().unwrap() > 1.4 && r["dispersion"].as_f64().unwrap() > 0.0);
    }
    let quartz = rows.iter().find(|r| r["name"] == "quartz").unwrap();
    // Handbook: quartz n_ω 1.544, B–G 0.013, ordinary ray.
    let nd = quartz["nd"].as_f64().unwrap();
    assert!((nd - 1.544).abs() < 0.003, "{nd}");
    assert!((quartz["dispersion"].as_f64().unwrap() - 0.013).abs() < 0.0013);
    assert_eq!(quartz["ordinary_ray"], true);
    assert!(quartz["source"].as_str().unwrap().contains("Ghosh"));
    assert!(quartz["formula"].as_str().unwrap().starts_with("Sellmeier"));
    let text = ok(d.path(), &["materials"]);
    assert!(
        text.contains("quartz") && text.contains("ordinary ray"),
        "{text}"
    );
}

#[test]
fn ri_n_bg_reaches_the_commands_and_bad_names_list_the_allowed_ones() {
    let d = tempdir().unwrap();
    let j: serde_json::Value = serde_json::from_str(&ok(
        d.path(),
        &["info", "tolkowsky", "--material", "ri:1.54:0.013", "--json"],
    ))
    .unwrap();
    assert_eq!(j["material"], "ri:1.54:0.013");
    bad(
        d.path(),
        &["info", "tolkowsky", "--material", "kryptonite"],
        &["--material", "quartz", "moissanite", "ri:N[:BG]"],
    );
    bad(
        d.path(),
        &["info", "tolkowsky", "--material", "ri:1.5:x"],
        &["--material", "BG `x` is not a number"],
    );
}
