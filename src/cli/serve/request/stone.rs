//! The stone a request asks for: its material, body colour, size and crystal settings, read
//! into the library's [`StoneChoice`] as the command line reads its flags and Python its
//! keywords, and each cut's stone made by it ([`StoneChoice::stones`]).

use super::*;
use facetlab::metrics::{ColourNotes, CrystalChoice, StoneChoice, StoneFields};
use facetlab::optics::{CrystalFields, OpticAxis};

/// The body's fields, as the library's errors name them.
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
    overrides: "a material sent overrides it",
};

/// The stones' choice: the material (`material`, else each cut's own), its body colour
/// (`colour`, `colour_density`), the size (`diameter_mm` or `size_mm`) and the crystal settings
/// (`optic_axis`, `birefringence`, `colour_e`), through the library's choosers that `score` and
/// `render` use for their flags; errors name the body's fields.
pub(super) fn stone(b: &Body) -> ApiResult<StoneChoice> {
    let name = match b.material.given() {
        Ok(n) => n.map(String::as_str),
        Err(_) => {
            return Err(ApiError::bad(
                "material",
                "must be a string such as \"amethyst\"",
            ))
        }
    };
    let material = Material::choose(
        name,
        None,
        MaterialFields {
            material: "material",
            ri: "ri",
        },
    )
    .map_err(invalid)?;
    let colour = match b.colour.given() {
        Ok(c) => c.map(|c| c.as_str()).filter(|c| !c.trim().is_empty()),
        Err(_) => {
            return Err(ApiError::bad(
                "colour",
                "must be a string such as \"#7a3fa0@10mm\" or \"lab(40,30,-40)\"",
            ))
        }
    };
    let density = match b.colour_density.given() {
        Ok(d) => d.map(|d| d.as_f64().unwrap_or(f64::NAN)),
        Err(v) => {
            return Err(ApiError::bad(
                "colour_density",
                format!("{} is not a number", short(&v.to_string())),
            ))
        }
    };
    let mut choice = StoneChoice::new(
        material,
        name.is_some(),
        colour.map(str::to_string),
        density,
        FIELDS.colour,
    )
    .map_err(invalid)?;
    // A uniaxial stone's optic axis (degrees from the table's normal, toward azimuth 0),
    // whether it is traced birefringent and its E ∥ c colour.
    let axis = match b.optic_axis.given() {
        Ok(a) => a
            .map(|a| {
                OpticAxis::new(
                    a.as_f64().unwrap_or(f64::NAN),
                    0.0,
                    FIELDS.crystal.optic_axis,
                )
            })
            .transpose()
            .map_err(invalid)?,
        Err(v) => {
            return Err(ApiError::bad(
                "optic_axis",
                format!(
                    "{} is not a number of degrees from the table's normal",
                    short(&v.to_string())
                ),
            ))
        }
    };
    let on = match b.birefringence.given() {
        Ok(o) => o.copied(),
        Err(_) => return Err(ApiError::bad("birefringence", "must be true or false")),
    };
    let colour_e = match b.colour_e.given() {
        Ok(c) => c.map(|c| c.as_str()).filter(|c| !c.trim().is_empty()),
        Err(_) => {
            return Err(ApiError::bad(
                "colour_e",
                "must be a string such as \"#c08040@10mm\"",
            ))
        }
    };
    choice.crystal = Some(CrystalChoice {
        birefringence: on,
        optic_axis: axis,
        colour_e: colour_e.map(str::to_string),
        wavelength_nm: facetlab::metrics::REFERENCE_WAVELENGTH_NM,
    });
    let size = match (b.diameter_mm.given(), b.size_mm.given()) {
        (Ok(Some(_)), Ok(Some(_))) => {
            return Err(ApiError::bad(
                "size_mm",
                "give either diameter_mm or size_mm, not both",
            ))
        }
        (Ok(Some(w)), _) => {
            StoneSize::width(w.as_f64().unwrap_or(f64::NAN), "diameter_mm").map_err(invalid)?
        }
        (_, Ok(Some(l))) => StoneSize::parse_length(l, "size_mm").map_err(invalid)?,
        (Err(v), _) => {
            return Err(ApiError::bad(
                "diameter_mm",
                format!("{} is not a number of millimetres", short(&v.to_string())),
            ))
        }
        (_, Err(_)) => {
            return Err(ApiError::bad(
                "size_mm",
                "must be a string: L or LxW in millimetres, e.g. \"10x5\"",
            ))
        }
        (Ok(None), Ok(None)) => StoneSize::default(),
    };
    choice.size_is_length = matches!(size, StoneSize::Length(_) | StoneSize::LengthWidth(..));
    choice.size = size;
    // Refused before any cut is built: a colour_e no stone takes, and the crystal settings a
    // material sent does not take.
    choice.check(&FIELDS).map_err(invalid)?;
    Ok(choice)
}

/// The stone `cut` is traced as ([`StoneChoice::stones`]): its material (the one sent, else
/// the cut's own, a design's index or notes; diamond for a family) with its body colour and
/// crystal settings, and its width in mm (a length follows from its L/W).
pub fn stone_for(r: &Req, cut: &facetlab::cut::Cut) -> ApiResult<(Material, f64)> {
    let s = r
        .stone
        .stones(
            std::slice::from_ref(cut),
            &FIELDS,
            ColourNotes::Traced,
            &mut |_, _| {},
        )
        .map_err(invalid)?;
    Ok((s.materials[0].clone(), s.widths[0]))
}
