//! A tie of tiers as a key names it (`P1+P2`, `C1=C2`), and where a free key stops keeping
//! its design ([`Breach`]): the plain types that [`super::DesignSpace`] reads from its keys and
//! that the searches of `ties.rs` answer with.

/// How a tie turns its tiers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TieKind {
    /// `A+B`: each tier turned by the same change of angle (the value, degrees).
    Together,
    /// `A=B`: every tier set to the value (degrees).
    Equal,
}

/// A tie of tiers as a key names it: `P1+P2` or `C1=C2`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tie {
    /// The tiers' names, as written.
    pub tiers: Vec<String>,
    /// How they turn.
    pub kind: TieKind,
}

impl Tie {
    /// The tie a key writes, if it is one: two or more names joined by `+` (turned together)
    /// or by `=` (set to one angle), not both.
    ///
    /// ```
    /// use facetlab::design::{Tie, TieKind};
    /// let t = Tie::parse("P1+P2").unwrap();
    /// assert_eq!((t.tiers.len(), t.kind), (2, TieKind::Together));
    /// assert_eq!(Tie::parse("C1 = C2 = C3").unwrap().key(), "C1=C2=C3");
    /// assert!(Tie::parse("P1").is_none() && Tie::parse("P1+P2=C1").is_none());
    /// ```
    pub fn parse(key: &str) -> Option<Tie> {
        let (sep, kind) = match (key.contains('+'), key.contains('=')) {
            (true, false) => ('+', TieKind::Together),
            (false, true) => ('=', TieKind::Equal),
            _ => return None,
        };
        let tiers: Vec<String> = key.split(sep).map(|s| s.trim().to_string()).collect();
        (tiers.len() >= 2 && tiers.iter().all(|t| !t.is_empty())).then_some(Tie { tiers, kind })
    }

    /// The key: the names joined by `+` or `=`.
    pub fn key(&self) -> String {
        let sep = match self.kind {
            TieKind::Together => "+",
            TieKind::Equal => "=",
        };
        self.tiers.join(sep)
    }
}

/// Where a free key stops keeping the design, found before a search.
#[derive(Clone, Debug, PartialEq)]
pub struct Breach {
    /// The free key.
    pub key: String,
    /// The first value (of those tried, to 0.005°) at which the design is not itself.
    pub at: f64,
    /// The values from the start toward `at` that keep it: (low, high).
    pub holds: (f64, f64),
    /// What happens there (a facet vanishes, an edge appears or vanishes, a meet opens).
    pub what: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ties_parse_both_ways_and_refuse_a_mix() {
        assert_eq!(Tie::parse("A=B").unwrap().kind, TieKind::Equal);
        assert_eq!(Tie::parse(" A + B + C ").unwrap().key(), "A+B+C");
        for bad in ["A", "A+", "+B", "A+B=C", "A++B"] {
            assert!(Tie::parse(bad).is_none(), "{bad}");
        }
    }
}
