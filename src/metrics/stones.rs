//! The stones a command traces: for every cut, its material (the caller's, else a design's
//! own: [`material_of`]), its body colour, its width in mm and its crystal settings, chosen
//! by one rule for `score`, `render`, `trace` and `report`, the Python package and the web
//! page. What the choice says to the user (a design traced in its own material, a coloured
//! stone's colour and width, how a birefringent stone is traced) comes out as notes ([`NoteKind`]),
//! each as soon as it is known, so that a later error follows the lines before it.

use super::material_of;
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::optics::{
    BodyColour, ColourFields, CrystalFields, Material, OpticAxis, StoneSize, UserColour,
};

/// `on`/`off` (also `true`/`false`, `yes`/`no`); an error names `field`.
pub fn on_off(field: &str, s: &str) -> Result<bool> {
    match s.trim().to_ascii_lowercase().as_str() {
        "on" | "true" | "yes" => Ok(true),
        "off" | "false" | "no" => Ok(false),
        _ => Err(Error::invalid(
            field,
            format!("`{s}` is not allowed; use on or off"),
        )),
    }
}

/// Where the caller took each setting of a stone, named in its errors and notes: the
/// command line's flags, the Python package's keyword arguments.
#[derive(Clone, Copy, Debug)]
pub struct StoneFields<'a> {
    /// The body colour and its density.
    pub colour: ColourFields<'a>,
    /// Birefringence, the optic axis and the E ∥ c colour.
    pub crystal: CrystalFields<'a>,
    /// The stone's width.
    pub width: &'a str,
    /// The stone's length (or length and width).
    pub length: &'a str,
    /// How the caller overrides a design's own material, said after the note that a design
    /// is traced in it (the command line's flags, the Python package's `material overrides`).
    pub overrides: &'a str,
}

/// The crystal settings of a uniaxial stone ([`Material::choose_crystal`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CrystalChoice {
    /// Traced birefringent (on) or with its ordinary ray alone (off); default: on for
    /// uniaxial stones.
    pub birefringence: Option<bool>,
    /// The optic axis (read by the face: [`OpticAxis::parse`], [`OpticAxis::new`]).
    pub optic_axis: Option<OpticAxis>,
    /// The E ∥ c colour.
    pub colour_e: Option<String>,
    /// The wavelength (nm) a birefringent stone's note gives its indices at.
    pub wavelength_nm: f64,
}

impl CrystalChoice {
    /// Read the E ∥ c colour as a uniaxial stone reads it, whatever stones it will be applied
    /// to, so a value no stone takes is refused before any work (the switch and the axis come
    /// read); the error names its field.
    pub fn check(&self, fields: &CrystalFields<'_>) -> Result<()> {
        if let Some(c) = &self.colour_e {
            BodyColour::from_colour(&UserColour::parse(c, fields.colour_e)?, fields.colour_e)?;
        }
        Ok(())
    }
}

/// What the caller chose for the stones; [`StoneChoice::stones`] makes each cut's.
#[derive(Clone, Debug)]
pub struct StoneChoice {
    /// The material of every cut the caller chose (`chosen`), else of every cut without one
    /// of its own, with its body colour.
    pub material: Material,
    /// Whether the caller chose the material (else a design is traced in its own).
    pub chosen: bool,
    /// The user's colour (`#rrggbb[@Nmm]`, `lab(L,a,b)[@Nmm]`).
    pub colour: Option<String>,
    /// A factor on the body colour's absorption.
    pub colour_density: Option<f64>,
    /// The stone's size.
    pub size: StoneSize,
    /// Whether the size was given as a length (its errors name `length`, else `width`).
    pub size_is_length: bool,
    /// The crystal settings, applied when given.
    pub crystal: Option<CrystalChoice>,
}

/// What a note is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoteKind {
    /// A design traced in its own material (or a malformed note ignored).
    Design,
    /// A coloured stone's colour and width.
    Colour,
    /// How a birefringent stone is traced.
    Crystal,
}

/// How a coloured stone's note reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColourNotes {
    /// The command traces the colour.
    Traced,
    /// The command does not ([`BodyColour::not_traced_note`]).
    NotTraced,
}

/// Every cut's stone: its material and width in mm, in the order of the cuts.
#[derive(Clone, Debug, Default)]
pub struct Stones {
    /// The material each cut is traced in.
    pub materials: Vec<Material>,
    /// Each cut's width in mm.
    pub widths: Vec<f64>,
}

impl Stones {
    /// A copy of `base` per cut, each in its stone's material (`with`), and `base` in the
    /// first cut's material (what a document's settings name); `base` itself without cuts.
    pub fn configs<C: Clone>(&self, base: &C, with: impl Fn(&C, Material) -> C) -> (C, Vec<C>) {
        let each: Vec<C> = self
            .materials
            .iter()
            .map(|m| with(base, m.clone()))
            .collect();
        let named = each.first().cloned().unwrap_or_else(|| base.clone());
        (named, each)
    }
}

impl StoneChoice {
    /// The choice with `material`'s body colour chosen ([`BodyColour::choose`]: the user's
    /// colour, else the material's own, times the density).
    pub fn new(
        material: Material,
        chosen: bool,
        colour: Option<String>,
        colour_density: Option<f64>,
        fields: ColourFields<'_>,
    ) -> Result<StoneChoice> {
        let mut material = material;
        material.choose_colour(colour.as_deref(), colour_density, fields)?;
        Ok(StoneChoice {
            material,
            chosen,
            colour,
            colour_density,
            size: StoneSize::default(),
            size_is_length: false,
            crystal: None,
        })
    }

    /// Check the choice before any cut is known: the crystal settings read
    /// ([`CrystalChoice::check`]) and, when the caller chose the material (every cut is then
    /// traced in it), taken by it. A cut's own material is checked by [`StoneChoice::stones`].
    pub fn check(&self, fields: &StoneFields<'_>) -> Result<()> {
        let Some(x) = &self.crystal else {
            return Ok(());
        };
        x.check(&fields.crystal)?;
        if self.chosen {
            self.material.clone().choose_crystal(
                x.birefringence,
                x.optic_axis,
                x.colour_e.as_deref(),
                self.colour_density,
                fields.crystal,
            )?;
        }
        Ok(())
    }

    /// Every cut's stone. Its notes go to `note` once every stone is chosen, in this order:
    /// each design traced in its own material, then each coloured stone (as `colour` says),
    /// then each birefringent stone; an error comes alone, no note before it.
    pub fn stones(
        &self,
        cuts: &[Cut],
        fields: &StoneFields<'_>,
        colour: ColourNotes,
        note: &mut dyn FnMut(NoteKind, String),
    ) -> Result<Stones> {
        let mut notes: Vec<(NoteKind, String)> = Vec::new();
        let stones = self.stones_noted(cuts, fields, colour, &mut |k, l| notes.push((k, l)))?;
        for (k, l) in notes {
            note(k, l);
        }
        Ok(stones)
    }

    fn stones_noted(
        &self,
        cuts: &[Cut],
        fields: &StoneFields<'_>,
        colour: ColourNotes,
        note: &mut dyn FnMut(NoteKind, String),
    ) -> Result<Stones> {
        self.check(fields)?;
        let mut materials = Vec::with_capacity(cuts.len());
        for c in cuts {
            let (m, said) = material_of(c, &self.material, self.chosen);
            for s in said {
                note(
                    NoteKind::Design,
                    if s.ends_with("; ignored") {
                        format!("{}: {s}", c.name)
                    } else {
                        format!("{}: {s}; {}", c.name, fields.overrides)
                    },
                );
            }
            materials.push(m);
        }
        let size_field = if self.size_is_length {
            fields.length
        } else {
            fields.width
        };
        let mut widths = Vec::with_capacity(cuts.len());
        for (cut, m) in cuts.iter().zip(materials.iter_mut()) {
            if m.colour.is_none() {
                m.choose_colour(self.colour.as_deref(), self.colour_density, fields.colour)?;
            }
            let w = self.size.width_mm(cut.ratios().l_w, size_field)?;
            widths.push(w);
            if let Some(c) = &m.colour {
                let line = match colour {
                    ColourNotes::Traced => c.note(w),
                    ColourNotes::NotTraced => c.not_traced_note(w),
                };
                note(NoteKind::Colour, format!("{}: {line}", cut.name));
            }
        }
        if let Some(x) = &self.crystal {
            for (cut, m) in cuts.iter().zip(materials.iter_mut()) {
                m.choose_crystal(
                    x.birefringence,
                    x.optic_axis,
                    x.colour_e.as_deref(),
                    self.colour_density,
                    fields.crystal,
                )?;
                if let Some(n) = m.birefringence_note(x.wavelength_nm, fields.crystal.birefringence)
                {
                    note(NoteKind::Crystal, format!("{}: {n}", cut.name));
                }
            }
        }
        Ok(Stones { materials, widths })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::GemcadRecord;

    const FIELDS: StoneFields<'static> = StoneFields {
        colour: ColourFields {
            colour: "body colour",
            density: "colour density",
        },
        crystal: CrystalFields {
            birefringence: "birefringence",
            optic_axis: "optic axis",
            colour_e: "E∥c colour",
        },
        width: "stone width",
        length: "stone length",
        overrides: "material overrides",
    };

    #[test]
    fn a_design_keeps_its_material_and_notes_come_in_order() {
        let round = crate::io::load_cut("tolkowsky").unwrap();
        let mut ruby = round.clone();
        ruby.name = "red".into();
        ruby.record = Some(GemcadRecord {
            footnotes: vec!["Material: ruby".into()],
            ..Default::default()
        });
        let mut choice =
            StoneChoice::new(Material::diamond(), false, None, None, FIELDS.colour).unwrap();
        choice.size = StoneSize::parse_length("8", "stone length").unwrap();
        choice.size_is_length = true;
        choice.crystal = Some(CrystalChoice {
            wavelength_nm: 589.3,
            ..Default::default()
        });
        let mut notes = Vec::new();
        let s = choice
            .stones(
                &[round.clone(), ruby],
                &FIELDS,
                ColourNotes::Traced,
                &mut |k, l| notes.push((k, l)),
            )
            .unwrap();
        assert_eq!(s.materials[0].name, "diamond");
        assert_eq!(s.materials[1].name, "ruby");
        // A round's L/W is 1: 8 mm long is 8 mm wide.
        assert!((s.widths[0] - 8.0).abs() < 1e-9 && (s.widths[1] - 8.0).abs() < 1e-9);
        let kinds: Vec<NoteKind> = notes.iter().map(|n| n.0).collect();
        assert_eq!(kinds[0], NoteKind::Design);
        assert_eq!(
            notes[0].1,
            "red: traced as ruby (the design's notes); material overrides"
        );
        assert!(kinds.contains(&NoteKind::Colour) && kinds.contains(&NoteKind::Crystal));
        let mut sorted = kinds.clone();
        sorted.sort_by_key(|k| *k as u8);
        assert_eq!(kinds, sorted, "design, then colour, then crystal notes");
        // A bad setting names its field, and comes alone: no note before it.
        choice.crystal = Some(CrystalChoice {
            colour_e: Some("maybe".into()),
            wavelength_nm: 589.3,
            ..Default::default()
        });
        let mut notes = Vec::new();
        let e = choice
            .stones(
                std::slice::from_ref(&round),
                &FIELDS,
                ColourNotes::Traced,
                &mut |_, l| notes.push(l),
            )
            .unwrap_err();
        assert!(e.to_string().starts_with("E∥c colour"), "{e}");
        assert!(notes.is_empty(), "{notes:?}");
        // A coloured biaxial stone (its colour a note) given an optic axis: the error alone.
        let mut peridot = StoneChoice::new(
            Material::by_name("peridot").unwrap(),
            true,
            None,
            None,
            FIELDS.colour,
        )
        .unwrap();
        peridot.crystal = Some(CrystalChoice {
            optic_axis: Some(OpticAxis::parse("30", "optic axis").unwrap()),
            wavelength_nm: 589.3,
            ..Default::default()
        });
        let e = peridot
            .stones(
                std::slice::from_ref(&round),
                &FIELDS,
                ColourNotes::Traced,
                &mut |_, l| notes.push(l),
            )
            .unwrap_err();
        assert!(
            e.to_string().starts_with("optic axis: peridot is biaxial"),
            "{e}"
        );
        assert!(notes.is_empty(), "{notes:?}");
        // Without the axis its colour's note is said.
        peridot.crystal = None;
        peridot
            .stones(&[round], &FIELDS, ColourNotes::Traced, &mut |_, l| {
                notes.push(l)
            })
            .unwrap();
        assert!(!notes.is_empty());
    }

    #[test]
    fn crystal_settings_are_read_before_any_stone() {
        let fields = FIELDS.crystal;
        let given = |c: Option<&str>| {
            CrystalChoice {
                birefringence: Some(false),
                optic_axis: Some(OpticAxis::parse("45@22.5", fields.optic_axis).unwrap()),
                colour_e: c.map(String::from),
                wavelength_nm: 589.3,
            }
            .check(&fields)
            .map_err(|e| e.to_string())
        };
        assert!(given(Some("#3050c0")).is_ok());
        assert!(given(Some("zzz")).unwrap_err().starts_with("E∥c colour:"));
        // The switch and the axis are read at each face's door, by these.
        assert!(on_off(fields.birefringence, "maybe")
            .unwrap_err()
            .to_string()
            .starts_with("birefringence:"));
        assert!(on_off(fields.birefringence, "Yes").unwrap());
        for bad in ["nan@5", "45@1e300"] {
            assert!(OpticAxis::parse(bad, fields.optic_axis)
                .unwrap_err()
                .to_string()
                .starts_with("optic axis:"));
        }
    }
}
