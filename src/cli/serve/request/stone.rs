//! The stone a request asks for: its material, body colour and size, read through the
//! library's choosers as the command line reads its flags.

use super::*;

/// The material (with its body colour) and the stone's size, through the library's choosers
/// that `score` and `render` use for `--material`, `--colour`, `--colour-density`,
/// `--diameter-mm` and `--size-mm`; errors name the body's fields.
/// The material, the size, and when no material was sent the colour fields (see [`Req::own`]).
type Stone = (Material, StoneSize, Option<(Option<String>, Option<f64>)>);

pub(super) fn stone(b: &Body) -> ApiResult<Stone> {
    let name = match b.material.given() {
        Ok(n) => n.map(String::as_str),
        Err(_) => {
            return Err(ApiError::bad(
                "material",
                "must be a string such as \"amethyst\"",
            ))
        }
    };
    let mut material = Material::choose(
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
    material
        .choose_colour(
            colour,
            density,
            ColourFields {
                colour: "colour",
                density: "colour_density",
            },
        )
        .map_err(invalid)?;
    // A uniaxial stone's optic axis (degrees from the table's normal, toward azimuth 0),
    // whether it is traced birefringent and its E ∥ c colour, through the chooser
    // `--optic-axis`, `--birefringence` and `--colour-e` use.
    let axis = match b.optic_axis.given() {
        Ok(a) => a
            .map(|a| {
                facetlab::optics::OpticAxis::new(a.as_f64().unwrap_or(f64::NAN), 0.0, "optic_axis")
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
    material
        .choose_crystal(
            on,
            axis,
            colour_e,
            density,
            facetlab::optics::CrystalFields {
                birefringence: "birefringence",
                optic_axis: "optic_axis",
                colour_e: "colour_e",
            },
        )
        .map_err(invalid)?;
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
    let own = name
        .is_none()
        .then(|| (colour.map(str::to_string), density));
    Ok((material, size, own))
}

/// The material `cut` is traced in: the one sent, else the cut's own (a design's index or
/// notes, [`facetlab::metrics::material_of`]; diamond for a family), coloured as sent.
pub fn material_for(r: &Req, cut: &facetlab::cut::Cut) -> ApiResult<Material> {
    let Some((colour, density)) = &r.own else {
        return Ok(r.material.clone());
    };
    let (mut m, _) = facetlab::metrics::material_of(cut, &Material::diamond(), false);
    m.choose_colour(
        colour.as_deref(),
        *density,
        ColourFields {
            colour: "colour",
            density: "colour_density",
        },
    )
    .map_err(invalid)?;
    Ok(m)
}

/// The stone's width in mm for `cut` (a length follows from its L/W).
pub fn width_mm(r: &Req, cut: &facetlab::cut::Cut) -> ApiResult<f64> {
    r.stone
        .width_mm(cut.ratios().l_w, "size_mm")
        .map_err(invalid)
}
