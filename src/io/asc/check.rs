//! The values of a GemCad design that both of its files carry — the refractive index, the
//! index gear and its offset, the symmetry — checked by one rule whichever file they come
//! from: a `.asc` line or a `.gem` trailer. Each reader names the place (`design.asc:4`,
//! `design.gem: byte 1234`) and adds the problem these functions describe.

/// A design's index (`I`) must be above this and at most [`RI_MAX`]: the rule of `--ri`
/// (`optics::Material::RI_ABOVE` and `RI_MAX`, which the `io` floor cannot import; a test of
/// the binary holds them equal).
pub const RI_ABOVE: f64 = 1.0;
/// The largest index a design may give (see [`RI_ABOVE`]).
pub const RI_MAX: f64 = 10.0;
/// The most teeth a gear may have.
pub const MAX_GEAR: f64 = 1000.0;

/// Why `n` cannot be a design's refractive index (GemCad's `I`), or `None` when it can: the
/// rule of `--ri`, an index in ([`RI_ABOVE`], [`RI_MAX`]].
pub(in crate::io) fn ri_problem(n: f64) -> Option<String> {
    (!(n > RI_ABOVE && n <= RI_MAX)).then(|| {
        format!(
            "refractive index {} is not allowed; give an index in ({RI_ABOVE}, {RI_MAX}], e.g. 1.54",
            crate::error::shown(n)
        )
    })
}

/// Why `teeth` cannot be a design's index gear, or `None` when it can: a whole, non-zero
/// tooth count up to [`MAX_GEAR`] (negative: the indices run clockwise).
pub(in crate::io) fn gear_problem(teeth: f64) -> Option<String> {
    (!(teeth != 0.0 && teeth.fract() == 0.0 && teeth.abs() <= MAX_GEAR)).then(|| {
        format!(
            "gear {} is not allowed; a design's gear is a whole, non-zero tooth count up to {MAX_GEAR} (negative: clockwise), e.g. 96",
            crate::error::shown(teeth)
        )
    })
}

/// Why `offset` cannot be the offset of a gear of `teeth` teeth, or `None` when it can: an
/// index, so a finite number within one turn of the gear, |`offset`| ≤ |`teeth`|. (Beyond
/// that an offset only repeats a smaller one, and a huge one, 1e18, swamps the facets'
/// indices in rounding: the design written again would put a tier's facets at one azimuth.)
pub(in crate::io) fn offset_problem(offset: f64, teeth: f64) -> Option<String> {
    (offset.abs().partial_cmp(&teeth.abs()) > Some(std::cmp::Ordering::Equal)
        || offset.is_nan()
        || teeth.is_nan())
    .then(|| {
        let t = crate::error::shown(teeth.abs());
        format!(
            "gear offset {} is not allowed; it is an index on the gear, from -{t} to {t}, e.g. 0",
            crate::error::shown(offset)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn design_values_have_one_rule() {
        assert!(ri_problem(1.54).is_none() && ri_problem(2.42).is_none());
        for bad in [0.0, -1.0, 1.0, 100.0, f64::NAN, f64::INFINITY] {
            let e = ri_problem(bad).unwrap();
            assert!(
                e.contains("refractive index") && e.contains("(1, 10]"),
                "{e}"
            );
        }
        for bad in [96.5, 2000.0, f64::NAN, f64::INFINITY] {
            assert!(gear_problem(bad).is_some(), "{bad}");
        }
        assert!(gear_problem(96.0).is_none() && gear_problem(-64.0).is_none());
        assert!(gear_problem(0.0).unwrap().contains("non-zero"));
        assert!(gear_problem(f64::NAN).is_some());
        assert!(offset_problem(48.0, 96.0).is_none() && offset_problem(-64.0, -64.0).is_none());
        for bad in [f64::INFINITY, f64::NAN, 96.5, -97.0, 1e18, -1e308] {
            let e = offset_problem(bad, 96.0).unwrap();
            assert!(e.contains("from -96 to 96"), "{e}");
        }
    }
}
