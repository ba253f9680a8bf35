//! Layouts ranked by value × colour (`src/plan/layout/by_colour.rs`): never worth less in
//! colour than the value layout's own stones, each stone's factor the single-plan colour
//! objective's chroma over the material's reference, the factor falling for a pale and a
//! dark stone, and a colourless material refused in one line.

use super::{box_rough, check_apart, config};
use crate::optics::Material;
use crate::plan::colour::{colour_factor, face_up_colour, reference_chroma};
use crate::plan::config::PriceTable;
use crate::plan::layout::{plan_layout, Layout, LayoutPlanner};
use crate::plan::{Objective, PlanConfig};
use glam::DVec3;

/// A price table whose price per carat jumps at `jump` carats.
fn prices(jump: f64) -> PriceTable {
    PriceTable {
        currency: "USD".into(),
        bands: vec![(0.0, 1000.0), (jump, 3000.0)],
        quality: Default::default(),
        ungraded: 1.0,
        included: None,
    }
}

/// Two round brilliants and ovals in a ruby box of two 2.5 mm cubes, its c-axis tilted, a
/// short search keeping two plans per family.
fn ruby_box() -> (crate::plan::Rough, PlanConfig, Material) {
    let (s, kerf, a) = (2.5, 0.3, 0.15);
    let rough = box_rough(2.0 * s + kerf, s, s);
    let mut cfg = config(2, kerf, a);
    cfg.families = vec!["round-brilliant".into(), "oval".into()];
    cfg.starts = 2;
    cfg.max_iterations = 60;
    cfg.saw_offsets = 2;
    cfg.top = 2;
    cfg.c_axis = Some(DVec3::new(0.3, -0.2, 0.9).normalize());
    (rough, cfg, Material::by_name("ruby").unwrap())
}

/// The layout's stones scored by worth × colour as the colour ranking scores them.
fn in_colour(l: &Layout, cfg: &PlanConfig, m: &Material, worth: &dyn Fn(f64) -> f64) -> f64 {
    let reference = reference_chroma(m).unwrap();
    l.stones
        .iter()
        .map(|s| {
            let c = face_up_colour(&s.plan, m, cfg.c_axis).unwrap();
            worth(s.plan.carats) * colour_factor(&c, reference)
        })
        .sum()
}

#[test]
fn a_colour_layout_is_worth_at_least_the_value_layouts_stones_in_colour() {
    let (rough, mut cfg, m) = ruby_box();
    let table = prices(0.2);
    cfg.objective = Objective::Value(table.clone());
    let valued = LayoutPlanner::new(&rough, &cfg, m.density, &[])
        .plan(&|| {})
        .unwrap();
    cfg.objective = Objective::Colour(Some(table.clone()));
    let coloured = plan_layout(&rough, &cfg, &m, &[], &|| {}, None).unwrap();
    let worth = |ct: f64| table.value(ct, None);
    let floor = in_colour(&valued, &cfg, &m, &worth);
    eprintln!(
        "value layout {:?} in colour {floor}; colour layout {:?} total {}",
        valued
            .stones
            .iter()
            .map(|s| s.plan.carats)
            .collect::<Vec<_>>(),
        coloured
            .stones
            .iter()
            .map(|s| (s.family.as_str(), s.plan.carats, s.colour))
            .collect::<Vec<_>>(),
        coloured.total
    );
    assert_eq!(coloured.stones.len(), valued.stones.len());
    assert!(floor > 0.0);
    assert!(
        coloured.total >= floor * (1.0 - 1e-12),
        "{} < {floor}",
        coloured.total
    );
    // The total is the stones' worth × factor, each worth the stone's price.
    let mut sum = 0.0;
    for s in &coloured.stones {
        let w = s.colour.expect("a stone ranked by colour");
        assert_eq!(w.worth, table.value(s.plan.carats, s.plan.grade));
        assert_eq!(s.plan.objective, w.worth * w.factor);
        sum += s.plan.objective;
    }
    assert!((sum - coloured.total).abs() <= 1e-12 * sum);
    // The pieces are the value layout's: the same saw plan, the stones apart.
    assert_eq!(coloured.saw, valued.saw);
    check_apart(&rough, &coloured, &cfg, &[]);
}

#[test]
fn a_stones_colour_factor_is_its_face_up_chroma_over_the_slabs_best() {
    let (rough, mut cfg, m) = ruby_box();
    cfg.families = vec!["oval".into()];
    cfg.top = 1;
    cfg.objective = Objective::Colour(None);
    let l = plan_layout(&rough, &cfg, &m, &[], &|| {}, None).unwrap();
    let reference = reference_chroma(&m).unwrap();
    assert_eq!(l.colour_reference, Some(reference));
    for s in &l.stones {
        let w = s.colour.unwrap();
        // Without a table a stone is worth its carats.
        assert_eq!(w.worth, s.plan.carats);
        let c = face_up_colour(&s.plan, &m, cfg.c_axis).unwrap();
        assert_eq!(w.factor, c.c / reference);
        assert_eq!(s.plan.colour.unwrap().c, c.c);
        assert!(w.factor > 0.0 && w.factor < 1.0, "{w:?}");
    }
    // The reference is the most chroma a slab shows, along either ray: no thickness shows
    // more.
    let rays = [m.colour.as_ref().unwrap(), m.colour_e().unwrap()];
    let best = (0..=2000)
        .flat_map(|i| {
            let mm = 10f64.powf(-2.0 + 5.0 * i as f64 / 2000.0);
            rays.map(|b| b.lab_through(mm))
        })
        .map(|lab| lab.y.hypot(lab.z))
        .fold(0.0, f64::max);
    assert!(best <= reference * (1.0 + 1e-9), "{best} {reference}");
    assert!(best >= reference * (1.0 - 1e-4), "{best} {reference}");
}

/// The factor falls for a pale stone and for a dark one: the same plan in a ruby of a
/// hundredth and of a hundred times its absorption (both rays) shows less colour than in ruby itself,
/// whose reference does not move with the density (a thicker or thinner slab gives back
/// the same colour).
#[test]
fn the_colour_factor_falls_for_a_pale_and_a_dark_stone() {
    let (rough, cfg, m) = ruby_box();
    let cut = crate::cut::Cut::from_family(
        "round",
        "round-brilliant",
        &std::collections::BTreeMap::new(),
    )
    .unwrap();
    let p = crate::plan::Planner::new(&rough, &cfg, m.density)
        .place(&cut, glam::DQuat::IDENTITY)
        .unwrap();
    let at = |density: f64| {
        let mut m = m.clone();
        let scaled = |b: crate::optics::BodyColour| b.with_density(density);
        m.colour = m.colour.map(scaled);
        let u = m.uniaxial.as_mut().unwrap();
        u.colour_e = u.colour_e.take().map(scaled);
        let r = reference_chroma(&m).unwrap();
        let c = face_up_colour(&p, &m, cfg.c_axis).unwrap();
        (r, colour_factor(&c, r))
    };
    let (pale, mid, dark) = (at(0.01), at(1.0), at(100.0));
    eprintln!("pale {pale:?} ruby {mid:?} dark {dark:?}");
    assert!((pale.0 - mid.0).abs() < 1e-6 * mid.0 && (dark.0 - mid.0).abs() < 1e-6 * mid.0);
    assert!(
        mid.1 > 2.0 * pale.1 && mid.1 > 2.0 * dark.1,
        "{pale:?} {mid:?} {dark:?}"
    );
}

/// A colourless material refuses a colour layout in one line naming `objective.kind`,
/// before any search; so does a grey one, whose slabs show no chroma.
#[test]
fn a_colourless_rough_refuses_a_colour_layout() {
    let (rough, mut cfg, _) = ruby_box();
    cfg.objective = Objective::Colour(None);
    for name in ["diamond", "sapphire"] {
        let m = Material::by_name(name).unwrap();
        let err = plan_layout(&rough, &cfg, &m, &[], &|| {}, None)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("objective.kind") && err.contains(name),
            "{err}"
        );
        assert!(!err.contains('\n'), "{err}");
    }
    let mut grey = Material::by_name("cubic-zirconia").unwrap();
    grey.colour =
        Some(crate::optics::BodyColour::new("grey", vec![0.3; 41], "a neutral absorber").unwrap());
    let err = plan_layout(&rough, &cfg, &grey, &[], &|| {}, None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("objective.kind") && err.contains("C*"),
        "{err}"
    );
    assert!(!err.contains('\n'), "{err}");
}
