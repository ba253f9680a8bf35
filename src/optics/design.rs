//! The material a design is traced in when the user names none: the stone its file was cut
//! for (GemCad's `I` line).

use super::Material;

/// How far a table material's n_D may be from a design's index and still be taken for it.
pub const DESIGN_INDEX_TOL: f64 = 0.005;

/// The material a design cut for refractive index `n` is traced in by default: the table
/// material ([`Material::table`]) whose n_D is closest to `n`, if within
/// [`DESIGN_INDEX_TOL`] (1.54 → quartz, 1.72 → spinel, 1.77 → sapphire), else `ri:N` (index N
/// with the generic dispersion of [`Material::by_name`]). `None` for an index `ri:N` does not
/// accept (N ≤ 1 or above 10).
///
/// ```
/// use facetlab::optics::design_material;
/// assert_eq!(design_material(1.54).unwrap().name, "quartz");
/// assert_eq!(design_material(1.61).unwrap().name, "ri:1.61");
/// assert!(design_material(0.9).is_none());
/// ```
pub fn design_material(n: f64) -> Option<Material> {
    let listed = Material::table()
        .into_iter()
        .map(|m| ((m.ri_d() - n).abs(), m))
        .filter(|(d, _)| *d <= DESIGN_INDEX_TOL + 1e-12)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, m)| m);
    listed.or_else(|| Material::by_name(&format!("ri:{n}")).ok())
}

/// The line saying how a design is traced: `traced as quartz (the design's index 1.54)`.
pub fn design_material_note(n: f64, m: &Material) -> String {
    format!("traced as {} (the design's index {n})", m.name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn design_indices_find_their_stones() {
        for (n, want) in [
            (1.54, "quartz"),
            (1.544, "quartz"),
            (1.72, "spinel"),
            (1.77, "sapphire"),
            (2.42, "diamond"),
        ] {
            assert_eq!(design_material(n).unwrap().name, want, "{n}");
        }
        let m = design_material(1.61).unwrap();
        assert_eq!(m.name, "ri:1.61");
        assert!((m.ri_d() - 1.61).abs() < 1e-9 && m.bg_dispersion() > 0.0);
        assert_eq!(
            design_material_note(1.54, &design_material(1.54).unwrap()),
            "traced as quartz (the design's index 1.54)"
        );
    }
}
