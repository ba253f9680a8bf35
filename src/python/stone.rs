//! The stone a Python call traces: its material, body colour, size and crystal settings from
//! keyword arguments, chosen as the command line chooses them from `--material`, `--ri`,
//! `--colour`, `--colour-density`, `--diameter-mm`/`--size-mm`, `--birefringence`,
//! `--optic-axis` and `--colour-e` (a design read from a file is traced in its own material
//! unless one is given). Errors name the keyword argument.

use super::args::{Number, Size};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::metrics::{
    ColourNotes, CrystalChoice, StoneChoice, StoneFields, REFERENCE_WAVELENGTH_NM,
};
use crate::optics::{ColourFields, CrystalFields, Material, MaterialFields, OpticAxis, StoneSize};

/// The keyword arguments that choose the stone.
#[derive(Clone, Debug, Default)]
pub(crate) struct StoneArgs {
    pub material: Option<String>,
    pub ri: Option<f64>,
    pub colour: Option<String>,
    pub colour_density: Option<f64>,
    pub size_mm: Option<String>,
    pub diameter_mm: Option<f64>,
    pub birefringence: Option<bool>,
    pub optic_axis: Option<String>,
    pub colour_e: Option<String>,
}

impl StoneArgs {
    /// The stone's keyword arguments as `score`, `score_many` and `render` take them (each
    /// signature spells them in this order, after its own).
    #[allow(clippy::too_many_arguments)]
    pub fn given(
        material: Option<String>,
        ri: Option<Number>,
        colour: Option<String>,
        colour_density: Option<Number>,
        size_mm: Option<Size>,
        diameter_mm: Option<Number>,
        birefringence: Option<bool>,
        optic_axis: Option<String>,
        colour_e: Option<String>,
    ) -> StoneArgs {
        StoneArgs {
            material,
            ri: ri.map(|n| n.0),
            colour,
            colour_density: colour_density.map(|n| n.0),
            size_mm: size_mm.map(|s| s.text()),
            diameter_mm: diameter_mm.map(|n| n.0),
            birefringence,
            optic_axis,
            colour_e,
        }
    }
}

/// Check a file a call writes (`path`) before any work: not a folder, replaced only with
/// `overwrite=True`, its folder present and writable (the library's check, as the command
/// line's outputs; its settings spelled as keywords, [`super::call::keyword`]).
pub(crate) fn refuse_existing(path: &std::path::Path, overwrite: bool) -> Result<()> {
    crate::io::guard::check_new_file(crate::io::guard::setting::OUTPUT, path, overwrite)
}

/// Where a Python call takes a stone's settings: its keyword arguments.
const FIELDS: StoneFields<'static> = StoneFields {
    colour: ColourFields {
        colour: "colour",
        density: "colour_density",
    },
    crystal: CrystalFields {
        birefringence: "birefringence",
        optic_axis: "optic_axis",
        colour_e: "colour_e",
    },
    width: "diameter_mm",
    length: "size_mm",
    overrides: "material overrides",
};

impl StoneArgs {
    /// Whether the caller chose a material (else a design is traced in its own).
    fn chosen(&self) -> bool {
        self.material.is_some() || self.ri.is_some()
    }

    /// The stone's size (default a width of 6.5 mm).
    pub fn size(&self) -> Result<StoneSize> {
        match (&self.diameter_mm, &self.size_mm) {
            (Some(_), Some(_)) => Err(Error::invalid(
                "size_mm",
                "give diameter_mm or size_mm, not both",
            )),
            (Some(w), None) => StoneSize::width(*w, "diameter_mm"),
            (None, Some(l)) => StoneSize::parse_length(l, "size_mm"),
            (None, None) => Ok(StoneSize::default()),
        }
    }

    /// The material `cut` is traced in, with its body colour and crystal settings, and its
    /// width in mm ([`StoneChoice::stones`], as the command line chooses them).
    pub fn material_for(&self, cut: &Cut) -> Result<(Material, f64)> {
        let s = self.choice()?.stones(
            std::slice::from_ref(cut),
            &FIELDS,
            ColourNotes::Traced,
            &mut |_, _| {},
        )?;
        Ok((s.materials[0].clone(), s.widths[0]))
    }

    /// The stones chosen as the command line chooses them from its flags.
    pub fn choice(&self) -> Result<StoneChoice> {
        let default = Material::choose(
            self.material.as_deref(),
            self.ri,
            MaterialFields {
                material: "material",
                ri: "ri",
            },
        )?;
        let mut choice = StoneChoice::new(
            default,
            self.chosen(),
            self.colour.clone(),
            self.colour_density,
            FIELDS.colour,
        )?;
        choice.size = self.size()?;
        choice.size_is_length = self.size_mm.is_some();
        choice.crystal = Some(CrystalChoice {
            birefringence: self.birefringence,
            optic_axis: self
                .optic_axis
                .as_deref()
                .map(|a| OpticAxis::parse(a, FIELDS.crystal.optic_axis))
                .transpose()?,
            colour_e: self.colour_e.clone(),
            wavelength_nm: REFERENCE_WAVELENGTH_NM,
        });
        Ok(choice)
    }
}
