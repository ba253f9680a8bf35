use super::*;
use std::collections::BTreeMap;

fn gia() -> Cut {
    crate::testkit::gia_round("gia", 40.7)
}

#[test]
fn gia_reference_matches_published_figures() {
    let c = gia();
    let p = c.proportions();
    assert!(
        (p.crown_height - 0.145).abs() < 0.0007,
        "crown height {}",
        p.crown_height
    );
    assert!(
        (p.pavilion_depth - 0.430).abs() < 0.0007,
        "pavilion depth {}",
        p.pavilion_depth
    );
    assert!(
        (p.total_depth - 0.600).abs() < 0.0007,
        "total depth {}",
        p.total_depth
    );
    assert!((p.table - 0.57).abs() < 1e-9);
    assert!((p.crown_angle - 34.0).abs() < 1e-9);
    assert!((p.pavilion_angle - 40.7).abs() < 1e-9);
    assert!((p.girdle - 0.025).abs() < 1e-9);
    let t = c.tiers();
    let angle = |n: &str| t.iter().find(|x| x.name == n).unwrap().angle;
    assert!(
        (angle("star") - 21.1).abs() < 0.05,
        "star {}",
        angle("star")
    );
    assert!(
        (angle("upper-half") - 40.6).abs() < 0.05,
        "upper half {}",
        angle("upper-half")
    );
    assert!(
        (angle("lower-half") - 41.8).abs() < 0.05,
        "lower half {}",
        angle("lower-half")
    );
    // 57 facets (no culet) + 16 girdle facets.
    assert_eq!(c.solid.facets().len(), 57 + 16);
    let count = |n: &str| t.iter().find(|x| x.name == n).unwrap().count;
    assert_eq!(
        (count("bezel"), count("star"), count("upper-half")),
        (8, 8, 16)
    );
    assert_eq!(
        (count("pavilion-main"), count("lower-half"), count("girdle")),
        (8, 16, 16)
    );
}

#[test]
fn set_and_validation() {
    let c = gia();
    let mut ch = BTreeMap::new();
    ch.insert("culet".to_string(), 0.02);
    let c2 = c.with_params(&ch).unwrap();
    assert_eq!(c2.solid.facets().len(), 58 + 16);
    ch.insert("table".into(), 57.0);
    let e = c.with_params(&ch).unwrap_err().to_string();
    assert!(e.starts_with("table:") && e.contains("0.57, not 57"), "{e}");
    let mut ch = BTreeMap::new();
    ch.insert("star".to_string(), 1.0);
    assert!(c
        .with_params(&ch)
        .unwrap_err()
        .to_string()
        .contains("(0, 1)"));
    let mut ch = BTreeMap::new();
    ch.insert("tabel".to_string(), 0.5);
    let e = c.with_params(&ch).unwrap_err().to_string();
    assert!(e.contains("tabel") && e.contains("table"), "{e}");
    let mut ch = BTreeMap::new();
    ch.insert("crown_angle".to_string(), f64::NAN);
    assert!(c
        .with_params(&ch)
        .unwrap_err()
        .to_string()
        .contains("not a number"));
}

#[test]
fn impossible_star_and_lower_half_are_named() {
    // At a 85 % table the bezel ridge meets the table plane at radius 0.92: a 50 % star
    // (tip at 0.893) would stand above the table.
    let mut v = BTreeMap::new();
    v.insert("table".to_string(), 0.85);
    let e = Cut::from_family("r", "round-brilliant", &v)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("star:") && e.contains("above the table"),
        "{e}"
    );
    v.insert("star".to_string(), 0.7);
    assert!(Cut::from_family("r", "round-brilliant", &v).is_ok());
    let mut v = BTreeMap::new();
    v.insert("culet".to_string(), 0.2);
    v.insert("lower_half".to_string(), 0.85);
    let e = Cut::from_family("r", "round-brilliant", &v)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("lower_half:") && e.contains("culet"), "{e}");
}

#[test]
fn random_parameters_build_or_say_which_parameter() {
    use rand::{Rng, SeedableRng};
    let fam = family("round-brilliant").unwrap();
    let mut rng = rand::rngs::SmallRng::seed_from_u64(7);
    let mut built = 0;
    for _ in 0..400 {
        let mut v = BTreeMap::new();
        for p in fam.params.iter().filter(|p| p.key != "girdle_facets") {
            v.insert(
                p.key.to_string(),
                p.min + (p.max - p.min) * rng.random_range(0.001..0.999),
            );
        }
        match Cut::from_family("r", "round-brilliant", &v) {
            Ok(c) => {
                let s = &c.solid;
                assert_eq!(s.vertices().len() + s.facets().len(), s.edges().len() + 2);
                assert!(s.volume() > 0.0);
                built += 1;
            }
            Err(e) => {
                let e = e.to_string();
                assert!(
                    e.starts_with("star:") || e.starts_with("lower_half:"),
                    "{e} for {v:?}"
                );
            }
        }
    }
    assert!(built > 200, "{built}");
}

#[test]
fn girdle_facet_counts() {
    for n in [32.0, 64.0] {
        let mut v = BTreeMap::new();
        v.insert("girdle_facets".to_string(), n);
        let c = Cut::from_family("r", "round-brilliant", &v).unwrap();
        assert_eq!(c.solid.facets().len(), 57 + n as usize);
    }
    let mut v = BTreeMap::new();
    v.insert("girdle".to_string(), 0.0);
    let knife = Cut::from_family("r", "round-brilliant", &v).unwrap();
    assert_eq!(knife.solid.facets().len(), 57);
    assert!(knife.proportions().girdle.abs() < 1e-12);
    let mut v = BTreeMap::new();
    v.insert("girdle_facets".to_string(), 20.0);
    assert!(Cut::from_family("r", "round-brilliant", &v).is_err());
}
