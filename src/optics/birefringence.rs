//! Choosing how a birefringent stone is traced: birefringence on or off, its optic axis and
//! its E ∥ c colour, from the command line (`--birefringence`, `--optic-axis`, `--colour-e`)
//! or a config (`[score] birefringence`, `optic_axis`, `colour_e`) through one chooser
//! ([`Material::choose_crystal`]), and the line and JSON that say how it was traced.

use super::body_colour::{BodyColour, UserColour};
use super::material::{Material, Optic, OpticAxis};
use crate::error::{Error, Result};

/// The names under which the birefringence settings reach [`Material::choose_crystal`], for
/// its error messages.
#[derive(Clone, Copy, Debug)]
pub struct CrystalFields<'a> {
    /// Where birefringence was switched on or off.
    pub birefringence: &'a str,
    /// Where the optic axis was given.
    pub optic_axis: &'a str,
    /// Where the E ∥ c colour was given.
    pub colour_e: &'a str,
}

/// Why biaxial stones (topaz, peridot) are traced with one index: see
/// [`Material::choose_crystal`].
pub const BIAXIAL_REASON: &str = "birefringence is traced for uniaxial stones; biaxial ones (topaz, peridot) are traced with their lowest index α: their three indices are known here only as handbook values (no published dispersion of β and γ, no spectra of their β and γ rays), and their modes need the quartic of Fresnel's equation of wave normals, not yet written";

impl Material {
    /// Apply the user's birefringence settings: `birefringence` on or off (default: on for
    /// uniaxial stones), the optic axis `axis` (read by the face: [`OpticAxis::parse`],
    /// [`OpticAxis::new`]) and the
    /// E ∥ c colour `colour_e` (a user colour as `--colour` takes it, times `density` when
    /// given). Errors name the field: an optic axis or E ∥ c colour for a stone that is not
    /// uniaxial, birefringence asked of a biaxial stone ([`BIAXIAL_REASON`]). Birefringence
    /// on for a singly refractive stone changes nothing.
    pub fn choose_crystal(
        &mut self,
        birefringence: Option<bool>,
        axis: Option<OpticAxis>,
        colour_e: Option<&str>,
        density: Option<f64>,
        fields: CrystalFields<'_>,
    ) -> Result<()> {
        let not_uniaxial = |field: &str, what: &str| {
            let kind = match self.optic {
                Optic::BiaxialAlpha => "biaxial",
                _ => "singly refractive",
            };
            Error::invalid(
                field,
                format!(
                    "{} is {kind}: {what} applies to uniaxial stones only (quartz, beryl, tourmaline, sapphire and ruby, zircon, moissanite and their varieties)",
                    self.name
                ),
            )
        };
        if birefringence == Some(true) && self.optic == Optic::BiaxialAlpha {
            return Err(Error::invalid(
                fields.birefringence,
                format!("{} is biaxial: {BIAXIAL_REASON}", self.name),
            ));
        }
        // The E ∥ c colour pairs with the stone's own (E ⟂ c) body colour: a colourless
        // stone is traced without absorption, so alone it would be ignored.
        if colour_e.is_some() && self.uniaxial.is_some() && self.colour.is_none() {
            return Err(Error::invalid(
                fields.colour_e,
                format!(
                    "{} has no body colour: the E∥c colour pairs with the stone's own (its E⊥c colour); give the stone a colour too, or a coloured variety (blue-sapphire, ruby, …)",
                    self.name
                ),
            ));
        }
        match self.uniaxial.as_mut() {
            Some(u) => {
                if let Some(on) = birefringence {
                    u.traced = on;
                }
                if let Some(a) = axis {
                    u.axis = a;
                }
                if let Some(text) = colour_e {
                    let c = BodyColour::from_colour(
                        &UserColour::parse(text, fields.colour_e)?,
                        fields.colour_e,
                    )?;
                    u.colour_e = Some(match density {
                        Some(d) => c.with_density(d),
                        None => c,
                    });
                }
                Ok(())
            }
            None => {
                if axis.is_some() {
                    return Err(not_uniaxial(fields.optic_axis, "an optic axis"));
                }
                if colour_e.is_some() {
                    return Err(not_uniaxial(fields.colour_e, "an E∥c colour"));
                }
                Ok(())
            }
        }
    }

    /// One line for stderr saying how a birefringent stone is traced (`None` for a singly
    /// refractive one): with both indices at `wavelength_nm` and the optic axis, or with the
    /// ordinary ray alone (birefringence off), or with α (biaxial). `switch` is how the face
    /// showing the line spells the birefringence setting (`--birefringence` on the command
    /// line, the `birefringence` keyword in Python).
    pub fn birefringence_note(&self, wavelength_nm: f64, switch: &str) -> Option<String> {
        if self.optic == Optic::BiaxialAlpha {
            return Some(format!(
                "{}: biaxial, traced with its lowest index α {:.4} ({BIAXIAL_REASON})",
                self.name,
                self.ri(wavelength_nm)
            ));
        }
        let u = self.uniaxial.as_ref()?;
        let (no, ne) = (self.ri(wavelength_nm), self.ri_e(wavelength_nm));
        if !u.traced {
            return Some(format!(
                "{}: birefringence off, traced with its ordinary index ω {no:.4} alone (ε {ne:.4} not traced)",
                self.name
            ));
        }
        let pleo = match &u.colour_e {
            Some(c) => format!("; E∥c colour {}", c.name),
            None if self.colour.is_some() => {
                "; no E∥c spectrum, the e-ray takes the E⊥c one".to_string()
            }
            None => String::new(),
        };
        Some(format!(
            "{}: birefringent, traced with ω {no:.4} and ε {ne:.4} at {wavelength_nm} nm, optic axis {} ({}){pleo}; {switch} off traces the ordinary ray alone",
            self.name,
            axis_words(u.axis),
            u.axis.label()
        ))
    }

    /// How a uniaxial stone was traced, for JSON (`None` for other stones).
    pub fn birefringence_json(&self, wavelength_nm: f64) -> Option<BirefringenceJson> {
        let u = self.uniaxial.as_ref()?;
        Some(BirefringenceJson {
            traced: u.traced,
            n_o: self.ri(wavelength_nm),
            n_e: self.ri_e(wavelength_nm),
            wavelength_nm,
            optic_axis: u.axis,
            colour_e: u.colour_e.as_ref().map(|c| c.name.clone()),
            source: u.source.clone(),
        })
    }
}

/// The optic axis in words: `c ⟂ table`, `c in the table's plane` or `c 35° from the table's
/// normal`.
fn axis_words(a: OpticAxis) -> String {
    if a.tilt_deg == 0.0 {
        "c ⟂ table".into()
    } else if a.tilt_deg == 90.0 {
        format!("c in the table's plane toward {}°", a.azimuth_deg)
    } else {
        format!(
            "c {}° from the table's normal toward {}°",
            a.tilt_deg, a.azimuth_deg
        )
    }
}

/// How a uniaxial stone was traced, as `score --json` and `render` write it under
/// `birefringence`: `traced` (false with `--birefringence off`), `n_o` and `n_e` at
/// `wavelength_nm`, `optic_axis` (`{tilt_deg, azimuth_deg}`), `colour_e` (the E ∥ c colour's
/// name, null when the stone has no E ∥ c spectrum) and `source` (of the extraordinary
/// index).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BirefringenceJson {
    /// Traced birefringent.
    pub traced: bool,
    /// Ordinary index at `wavelength_nm`.
    pub n_o: f64,
    /// Extraordinary index at `wavelength_nm`.
    pub n_e: f64,
    /// The wavelength of the two indices, nm.
    pub wavelength_nm: f64,
    /// The optic axis in the stone.
    pub optic_axis: OpticAxis,
    /// The E ∥ c colour's name.
    pub colour_e: Option<String>,
    /// Where the extraordinary index comes from.
    pub source: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    const F: CrystalFields = CrystalFields {
        birefringence: "birefringence",
        optic_axis: "optic axis",
        colour_e: "extraordinary colour",
    };

    #[test]
    fn the_chooser_sets_axis_and_switch_and_names_the_field() {
        // An E ∥ c colour needs the stone's own colour beside it: alone it is refused.
        let e = Material::by_name("tourmaline")
            .unwrap()
            .choose_crystal(None, None, Some("#40a060@5mm"), None, F)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("extraordinary colour: tourmaline has no body colour"),
            "{e}"
        );
        let mut m = Material::by_name("tourmaline").unwrap();
        m.colour = Some(
            BodyColour::from_colour(&UserColour::parse("#40a060", "c").unwrap(), "c").unwrap(),
        );
        m.choose_crystal(
            Some(false),
            Some(OpticAxis::parse("35@20", "optic axis").unwrap()),
            Some("#40a060@5mm"),
            Some(2.0),
            F,
        )
        .unwrap();
        let u = m.uniaxial.as_ref().unwrap();
        assert!(!u.traced && u.axis.tilt_deg == 35.0 && u.axis.azimuth_deg == 20.0);
        assert_eq!(u.colour_e.as_ref().unwrap().density, 2.0);
        assert!(m
            .birefringence_note(589.3, "birefringence")
            .unwrap()
            .contains("birefringence off"));
        m.choose_crystal(Some(true), None, None, None, F).unwrap();
        let note = m.birefringence_note(589.3, "birefringence").unwrap();
        assert!(
            note.contains("birefringent")
                && note.contains("35° from the table's normal")
                && note.ends_with("; birefringence off traces the ordinary ray alone"),
            "{note}"
        );
        // An axis out of range is refused where it is read, as text or as numbers.
        for e in [
            OpticAxis::parse("95", "optic axis").unwrap_err(),
            OpticAxis::new(95.0, 0.0, "optic axis").unwrap_err(),
        ] {
            let e = e.to_string();
            assert!(
                e.starts_with("optic axis: `95` is not an optic axis"),
                "{e}"
            );
        }
        assert_eq!(
            OpticAxis::new(45.0, 22.5, "a").unwrap(),
            OpticAxis::parse("45@22.5", "a").unwrap()
        );
        assert!(OpticAxis::new(f64::NAN, 0.0, "a").is_err());
        let mut d = Material::diamond();
        d.choose_crystal(Some(true), None, None, None, F).unwrap();
        assert!(
            d.birefringence_note(589.3, "birefringence").is_none()
                && d.birefringence_json(589.3).is_none()
        );
        let e = d
            .choose_crystal(
                None,
                Some(OpticAxis::parse("90", "optic axis").unwrap()),
                None,
                None,
                F,
            )
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("optic axis: diamond is singly refractive"),
            "{e}"
        );
        let mut t = Material::by_name("topaz").unwrap();
        let e = t
            .choose_crystal(Some(true), None, None, None, F)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("birefringence: topaz is biaxial"), "{e}");
        assert!(t.choose_crystal(Some(false), None, None, None, F).is_ok());
        assert!(t
            .birefringence_note(589.3, "birefringence")
            .unwrap()
            .contains("lowest index α"));
        let j = Material::by_name("sapphire")
            .unwrap()
            .birefringence_json(589.3)
            .unwrap();
        assert!(j.traced && j.n_o > j.n_e && j.optic_axis.tilt_deg == 0.0);
    }
}
