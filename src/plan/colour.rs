//! The face-up colour objective of a coloured rough (`[objective] kind = "colour"`, issue 41):
//! which of the plans a coloured rough allows shows the best colour face-up.
//!
//! The measure is the chroma C*ab of the stone's mean face-up colour (`score`'s `colour.c`:
//! its ISO picture drawn in colour, each band absorbed exactly along its paths). For a
//! cutter orienting a coloured rough it says the one thing they orient for: how much colour
//! the stone shows. It falls both ways from the best: a pale stone shows little colour, and a
//! dark one (a tourmaline with its c-axis up, "closed", where every face-up sight line sees
//! only the strongly absorbed ordinary ray) turns towards black, where C* goes to 0 with L*.
//! So a dark pleochroic rough is steered to its c-axis in the table and a pale one to its
//! c-axis up, the cutters' rules, from the physics alone.
//!
//! Each plan is scored as it would be cut: at its own width (absorption grows with the
//! size), with the optic axis where the rough's `[rough] c_axis` puts it
//! ([`super::Plan::optic_axis`]), at the fast score settings of the plan's other scores
//! ([`ScoreConfig::fast`]: 6 bands, split to 1e-4 of the light). The fast path: the weight
//! search finds each family's plans (scoring colour inside the search would cost a full
//! trace per step), then they are ranked by colour, one face-up trace per band each.
//!
//! A layout of several stones (`--stones N`) is ranked by value × colour: each stone's worth
//! (its price-table value, or its carats without a table) times its **colour factor**, its
//! face-up C* over the material's [`reference_chroma`] (the most chroma a plain slab of it
//! shows in daylight, at its best thickness): about the share of the material's most vivid
//! colour the stone shows face-up, falling for a too-pale and for a too-dark stone as C*
//! does (`src/plan/layout/by_colour.rs` ranks the stones).

use super::{Objective, Plan, PlanConfig};
use crate::error::{Error, Result};
use crate::metrics::{colour_of, ScoreConfig};
use crate::optics::{Material, StoneSize};
use crate::render::ColourStats;

/// Refuse `kind = "colour"` for a colourless material: one line naming `objective.kind`.
pub fn check(config: &PlanConfig, material: &Material) -> Result<()> {
    if matches!(config.objective, Objective::Colour(_)) && material.colour.is_none() {
        return Err(Error::invalid(
            "objective.kind",
            format!(
                "kind = \"colour\" needs a coloured material; {} has no body colour (allowed: a coloured variety such as ruby, emerald or blue-sapphire, `facetlab materials`; or kind = \"weight\")",
                material.name
            ),
        ));
    }
    Ok(())
}

/// The score settings of plan `p`'s face-up colour: the fast ones, with the material's
/// optic axis where `c_axis` (the rough's) puts it and the plan's own width.
pub fn colour_config(p: &Plan, material: &Material, c_axis: Option<glam::DVec3>) -> ScoreConfig {
    let mut m = material.clone();
    if let (Some(c), Some(u)) = (c_axis, m.uniaxial.as_mut()) {
        u.axis = p.optic_axis(c);
    }
    ScoreConfig {
        material: m,
        size: StoneSize::Width(p.scale),
        ..ScoreConfig::fast()
    }
}

/// Plan `p`'s face-up colour (`None` for a colourless material).
pub fn face_up_colour(
    p: &Plan,
    material: &Material,
    c_axis: Option<glam::DVec3>,
) -> Option<ColourStats> {
    colour_of(&p.cut.solid, &colour_config(p, material, c_axis))
}

/// The reference chroma of a layout's colour factor: the largest C*ab of D65 light through a
/// plain slab of `material`, over thicknesses from 1 µm to 10 m (a scan of 141 thicknesses
/// evenly in their logarithm, refined by golden section) and both rays of a pleochroic
/// stone. A slab shows no colour at zero thickness and none once it turns black, so the
/// largest lies between. `None` for a colourless material.
pub fn reference_chroma(material: &Material) -> Option<f64> {
    let most = |b: &crate::optics::BodyColour| {
        let f = |log_mm: f64| {
            let lab = b.lab_through(10f64.powf(log_mm));
            lab.y.hypot(lab.z)
        };
        let (n, lo, hi) = (141, -3.0, 4.0);
        let x = |i: usize| lo + (hi - lo) * i as f64 / (n - 1) as f64;
        let best = (0..n).max_by(|&a, &b| f(x(a)).total_cmp(&f(x(b))).then(b.cmp(&a)));
        let best = best.unwrap_or(0);
        let (mut a, mut b) = (x(best.saturating_sub(1)), x((best + 1).min(n - 1)));
        let r = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..60 {
            let (c, d) = (b - r * (b - a), a + r * (b - a));
            if f(c) >= f(d) {
                b = d;
            } else {
                a = c;
            }
        }
        f(x(best)).max(f(0.5 * (a + b)))
    };
    let rays = material.colour.iter().chain(material.colour_e());
    rays.map(most).reduce(f64::max)
}

/// The colour factor of a stone whose face-up colour is `c`: its chroma over the material's
/// [`reference_chroma`] `reference`.
pub fn colour_factor(c: &ColourStats, reference: f64) -> f64 {
    c.c / reference
}

/// Rank a family's `plans` by their face-up colour's chroma C*, most colour first (the plans
/// that miss the config's grade after those that meet it, as the weight search keeps them):
/// each plan's `objective` becomes its C* and its `colour` the statistics. Plans are scored
/// in parallel; the order does not depend on the number of threads.
pub fn rank_by_colour(
    plans: &mut [Plan],
    config: &PlanConfig,
    material: &Material,
    meets_grade: impl Fn(&Plan) -> bool,
) {
    use rayon::prelude::*;
    let colours: Vec<Option<ColourStats>> = plans
        .par_iter()
        .map(|p| face_up_colour(p, material, config.c_axis))
        .collect();
    for (p, c) in plans.iter_mut().zip(colours) {
        p.objective = c.map_or(0.0, |c| c.c);
        p.colour = c;
    }
    plans.sort_by(|a, b| {
        meets_grade(b)
            .cmp(&meets_grade(a))
            .then(b.objective.total_cmp(&a.objective))
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::Cut;
    use crate::optics::{BodyColour, UserColour};
    use crate::plan::{load_rough, plan_families, Planner};
    use glam::{DQuat, DVec3};
    use std::collections::BTreeMap;

    fn colour(text: &str) -> BodyColour {
        BodyColour::from_colour(&UserColour::parse(text, "colour").unwrap(), "colour").unwrap()
    }

    /// A strongly pleochroic tourmaline-like stone: a dark green ordinary ray (E⊥c, the
    /// "closed" colour along the c-axis) and a light green extraordinary ray (E∥c).
    fn pleochroic() -> Material {
        let mut m = Material::by_name("tourmaline").unwrap();
        m.colour = Some(colour("#1f5a36@2mm"));
        m.uniaxial.as_mut().unwrap().colour_e = Some(colour("#8fcf9a@2mm"));
        m
    }

    /// Two plans of one round brilliant in an octahedron, the same cut at the same size by the
    /// rough's symmetry, one table facing z, the other x: with the c-axis along z the plan
    /// whose table faces x (c-axis in its table, the light E∥c ray seen face-up) shows more
    /// colour and ranks first; with the c-axis along x the ranking turns over. A plan whose
    /// table faces its c-axis gives the same colour in either (the same stone).
    #[test]
    fn the_c_axis_ranks_the_plan_that_keeps_it_out_of_the_table_first() {
        let rough = load_rough("octahedron", Some(5.0)).unwrap();
        let m = pleochroic();
        let cut = Cut::from_family("round", "round-brilliant", &BTreeMap::new()).unwrap();
        let config = PlanConfig {
            objective: Objective::Colour(None),
            ..PlanConfig::default()
        };
        let planner = Planner::new(&rough, &config, m.density);
        let up_z = planner.place(&cut, DQuat::IDENTITY).unwrap();
        let up_x = planner
            .place(&cut, DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2))
            .unwrap();
        assert!((up_x.up() - DVec3::X).length() < 1e-12);
        assert!((up_z.scale - up_x.scale).abs() < 1e-6 * up_z.scale);
        let mut seen = Vec::new();
        for (c_axis, first) in [(DVec3::Z, DVec3::X), (DVec3::X, DVec3::Z)] {
            let cfg = PlanConfig {
                c_axis: Some(c_axis),
                ..config.clone()
            };
            let mut plans = vec![up_z.clone(), up_x.clone()];
            rank_by_colour(&mut plans, &cfg, &m, |_| true);
            let (best, other) = (&plans[0], &plans[1]);
            let (b, o) = (best.colour.unwrap(), other.colour.unwrap());
            eprintln!("c-axis {c_axis}: best {b:?}\n  other {o:?}");
            assert!((best.up() - first).length() < 1e-9, "c-axis {c_axis}");
            assert!(b.c > o.c + 1.0 && b.l > o.l, "{b:?} vs {o:?}");
            assert_eq!(best.objective, b.c);
            assert_eq!(other.optic_axis(c_axis).tilt_deg, 0.0);
            assert_eq!(best.optic_axis(c_axis).tilt_deg, 90.0);
            seen.push(o.c);
        }
        // The closed plan is the same stone in both runs.
        assert!((seen[0] - seen[1]).abs() < 1e-6 * seen[0], "{seen:?}");
    }

    /// `kind = "colour"` is read from a config, and a colourless material refuses it in one
    /// line naming `objective.kind`, before any search.
    #[test]
    fn a_colourless_rough_refuses_the_colour_objective() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plan.toml");
        std::fs::write(&path, "[objective]\nkind = \"colour\"\n").unwrap();
        let config = PlanConfig::load(&path).unwrap();
        assert_eq!(config.objective, Objective::Colour(None));
        let rough = load_rough("octahedron", Some(5.0)).unwrap();
        for name in ["sapphire", "diamond"] {
            let m = Material::by_name(name).unwrap();
            let err = plan_families(&rough, &config, &m, &|_| true, &|| {}, None)
                .unwrap_err()
                .to_string();
            assert!(
                err.contains("objective.kind") && err.contains(name),
                "{err}"
            );
            assert!(!err.contains('\n'), "{err}");
        }
        assert!(check(&config, &Material::by_name("ruby").unwrap()).is_ok());
        std::fs::write(&path, "[objective]\nkind = \"hue\"\n").unwrap();
        let err = PlanConfig::load(&path).unwrap_err().to_string();
        assert!(
            err.contains("objective.kind") && err.contains("colour"),
            "{err}"
        );
    }
}
