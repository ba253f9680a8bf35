//! The material a cut is traced in: the one rule of the command line's commands, the Python
//! package and the workbench ([`material_of`]).

use crate::cut::Cut;
use crate::optics::Material;

/// The material `cut` is traced in, and the lines saying why (for the user). When the caller
/// chose a material (`chosen`: a `--material`/`--ri` or its keyword), `default` (that
/// material). Otherwise a design is traced in its own ([`Material::of_design`]): the material
/// of its index (GemCad's `I` line), then the material, colour or optic axis its title and
/// notes name (`F Material: ruby`); a cut without either, and every family's cut, in
/// `default`.
///
/// ```
/// use facetlab::metrics::material_of;
/// use facetlab::optics::Material;
/// let mut cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// cut.record = Some(facetlab::cut::GemcadRecord {
///     footnotes: vec!["Material: ruby".into()],
///     ..Default::default()
/// });
/// let (m, why) = material_of(&cut, &Material::diamond(), false);
/// assert_eq!((m.name.as_str(), why[0].as_str()), ("ruby", "traced as ruby (the design's notes)"));
/// let (m, why) = material_of(&cut, &Material::cubic_zirconia(), true);
/// assert_eq!(m.name, "cubic-zirconia");
/// assert!(why.is_empty());
/// ```
pub fn material_of(cut: &Cut, default: &Material, chosen: bool) -> (Material, Vec<String>) {
    if chosen {
        return (default.clone(), Vec::new());
    }
    let lines = cut
        .record
        .iter()
        .flat_map(|r| r.title.iter().chain(&r.footnotes));
    Material::of_design(cut.design_ri(), lines, default)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::GemcadRecord;

    #[test]
    fn a_design_is_traced_in_its_own_material_unless_one_is_chosen() {
        let mut quartz = crate::io::load_cut("tolkowsky").unwrap();
        quartz.record = Some(GemcadRecord {
            ri: Some(1.54),
            ..Default::default()
        });
        let (m, why) = material_of(&quartz, &Material::diamond(), false);
        assert_eq!(m.name, "quartz");
        assert_eq!(why, ["traced as quartz (the design's index 1.54)"]);
        // Its index first, then a note naming a coloured variety in its title.
        let mut noted = quartz.clone();
        if let Some(r) = noted.record.as_mut() {
            r.title.push("Material: amethyst".into());
        }
        let (m, why) = material_of(&noted, &Material::diamond(), false);
        assert_eq!(m.name, "amethyst");
        assert!(m.colour.is_some() && why.len() == 2, "{why:?}");
        // A malformed note is said and ignored.
        if let Some(r) = noted.record.as_mut() {
            r.title[0] = "Material: kryptonite".into();
        }
        let (m, why) = material_of(&noted, &Material::diamond(), false);
        assert_eq!(m.name, "quartz");
        assert!(why[1].ends_with("; ignored"), "{why:?}");
        // A chosen material wins; a family's cut takes the default.
        for chosen in [true, false] {
            let family = crate::io::load_cut("gia-reference").unwrap();
            let (m, why) = material_of(&family, &Material::cubic_zirconia(), chosen);
            assert_eq!(m.name, "cubic-zirconia");
            assert!(why.is_empty());
        }
        let (m, _) = material_of(&noted, &Material::cubic_zirconia(), true);
        assert_eq!(m.name, "cubic-zirconia");
    }
}
