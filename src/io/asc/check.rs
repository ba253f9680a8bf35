//! The values of a GemCad design that both of its files carry — the refractive index, the
//! index gear and its offset, the symmetry — checked by one rule whichever file they come
//! from: a `.asc` line or a `.gem` trailer. Each reader names the place (`design.asc:4`,
//! `design.gem: byte 1234`) and adds the problem these functions describe.

/// Why `n` cannot be a design's refractive index (GemCad's `I`), or `None` when it can: a
/// positive finite number.
pub(in crate::io) fn ri_problem(n: f64) -> Option<String> {
    (!(n.is_finite() && n > 0.0)).then(|| {
        format!(
            "refractive index {n} is not allowed; a design's index is a positive number, e.g. 1.54"
        )
    })
}

/// Why `teeth` cannot be a design's index gear, or `None` when it can: a finite, non-zero
/// tooth count (negative: the indices run clockwise).
pub(in crate::io) fn gear_problem(teeth: f64) -> Option<String> {
    (!(teeth.is_finite() && teeth != 0.0)).then(|| {
        format!("gear {teeth} is not allowed; a design's gear has a non-zero tooth count, e.g. 96")
    })
}

/// Why `offset` cannot be a gear offset (an index), or `None` when it can: a finite number.
pub(in crate::io) fn offset_problem(offset: f64) -> Option<String> {
    (!offset.is_finite())
        .then(|| format!("gear offset {offset} is not allowed; it is an index, e.g. 0"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn design_values_have_one_rule() {
        assert!(ri_problem(1.54).is_none() && ri_problem(2.42).is_none());
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = ri_problem(bad).unwrap();
            assert!(
                e.contains("refractive index") && e.contains("positive"),
                "{e}"
            );
        }
        assert!(gear_problem(96.0).is_none() && gear_problem(-64.0).is_none());
        assert!(gear_problem(0.0).unwrap().contains("non-zero"));
        assert!(gear_problem(f64::NAN).is_some());
        assert!(offset_problem(48.0).is_none() && offset_problem(f64::INFINITY).is_some());
    }
}
