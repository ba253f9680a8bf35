//! Tied tiers, and what a design space checks before a search.
//!
//! Many designs are **rigid tier by tier**: each tier is cut to meet points its predecessors
//! set, so no single tier can turn without opening a meet; several turned together can. A
//! **tie** makes them one parameter of the [`DesignSpace`]: `P1+P2` turns each of its tiers by
//! the same change of angle (its value is that change, in degrees; 0 is the design), `C1=C2`
//! sets them all to one angle. A tier is in at most one key of a set of values.
//!
//! When a tier cannot turn alone, [`DesignSpace::tie_for`] finds the smallest tie of it with
//! other tiers that keeps every meet, by the same meet analysis that refused it (the depth
//! solve of [`super::TierModel::reangled`]): first the tiers it shares a meet with, one, two
//! or three of them, then the tiers of every meet still opened, added until none opens and
//! pruned back to the fewest.
//!
//! Before a search, [`DesignSpace::breaches`] walks each free key from its start to its
//! bounds and names the first angle where the design stops being itself (a facet would
//! vanish, an edge appear or vanish, a meet open), with the range that holds.

use super::space::DesignSpace;
use super::tie_key::{Breach, TieKind};
use crate::cut::CutSpace;
use crate::error::{Error, Result};
use std::collections::{BTreeMap, BTreeSet};

/// Steps from the start to each bound, and the bisection's last interval (degrees).
const STEPS: usize = 16;
const RESOLUTION: f64 = 0.005;

/// Tie searches stop after this many depth solves.
const TIE_BUDGET: usize = 400;

impl DesignSpace {
    /// The smallest tie of `key`'s tiers with others, turned together, that keeps every meet
    /// when `key` is at `value` (its tiers turned by the change that makes): `P1+P2`. `None`
    /// when `key` keeps every meet already, or no tie of up to the tiers of every meet it
    /// opens does.
    ///
    /// ```
    /// use facetlab::design::{DesignSpace, OpenMeets, MEET_TOL};
    /// // A square crown of two tiers meeting at an apex: neither turns alone, both together.
    /// let asc = "g 96 0.0\na -90 0.5 96 24 48 72 n G\na 40 0.35969603 96 48 n A\n\
    ///            a 40 0.35969603 24 72 n B\na 0 -0.3 96 n U\n";
    /// let cut = facetlab::io::asc::parse(asc.as_bytes(), "p").unwrap().to_cut("p").unwrap();
    /// let space = DesignSpace::new(&cut, MEET_TOL, OpenMeets::Refuse).unwrap();
    /// assert_eq!(space.tie_for("A", 41.0).as_deref(), Some("A+B"));
    /// ```
    pub fn tie_for(&self, key: &str, value: f64) -> Option<String> {
        let (tiers, delta) = self.change_of(key, value).ok()?;
        let opens = |set: &BTreeSet<usize>| self.opened_by(set, delta);
        let mut budget = TIE_BUDGET;
        let base: BTreeSet<usize> = tiers.iter().copied().collect();
        let first = opens(&base)?;
        if first.is_empty() {
            return None;
        }
        // The tiers sharing a meet with the key's, nearest first (in tier order).
        let shares: BTreeSet<usize> = self
            .model
            .meets
            .iter()
            .filter(|m| {
                m.facets
                    .iter()
                    .any(|&f| base.contains(&self.model.tier_of[f]))
            })
            .flat_map(|m| m.facets.iter().map(|&f| self.model.tier_of[f]))
            .filter(|t| self.key_tiers.contains(t) && !base.contains(t))
            .collect();
        let near: Vec<usize> = shares.into_iter().collect();
        for size in 1..=near.len().min(3) {
            for pick in combinations(near.len(), size) {
                if budget == 0 {
                    return None;
                }
                budget -= 1;
                let mut set = base.clone();
                set.extend(pick.iter().map(|&i| near[i]));
                if opens(&set).is_some_and(|o| o.is_empty()) {
                    return Some(self.tie_key(&set));
                }
            }
        }
        // Grow by the tiers of every meet still opened, then drop what is not needed.
        let mut set = base.clone();
        let mut opened = first;
        while !opened.is_empty() {
            let more: Vec<usize> = opened
                .iter()
                .flat_map(|&m| self.model.meets[m].facets.iter())
                .map(|&f| self.model.tier_of[f])
                .filter(|t| self.key_tiers.contains(t) && !set.contains(t))
                .collect();
            if more.is_empty() || budget == 0 {
                return None;
            }
            budget -= 1;
            set.extend(more);
            opened = opens(&set)?;
        }
        let extra: Vec<usize> = set.difference(&base).copied().collect();
        for t in extra.into_iter().rev() {
            let mut fewer = set.clone();
            fewer.remove(&t);
            if budget > 0 && opens(&fewer).is_some_and(|o| o.is_empty()) {
                set = fewer;
            }
            budget = budget.saturating_sub(1);
        }
        Some(self.tie_key(&set))
    }

    /// `key`'s tiers and the change of angle `value` gives them (a tier key: its new angle
    /// less its own; a `+` tie: the value; a `=` tie: the value less the tiers' mean).
    pub(super) fn change_of(&self, key: &str, value: f64) -> Result<(Vec<usize>, f64)> {
        let (tiers, kind) = self.resolve(key)?;
        let mean = tiers.iter().map(|&t| self.angles[t]).sum::<f64>() / tiers.len() as f64;
        let delta = match kind {
            Some(TieKind::Together) => value,
            _ => value - mean,
        };
        Ok((tiers, delta))
    }

    /// The meets that open when the tiers of `set` all turn by `delta` (none: `Some(empty)`);
    /// `None` when the solve fails or an angle leaves (0, 90).
    fn opened_by(&self, set: &BTreeSet<usize>, delta: f64) -> Option<Vec<usize>> {
        let mut angles = vec![None; self.model.names.len()];
        for &t in set {
            let a = self.angles[t] + delta;
            if !(a > 0.0 && a < 90.0) {
                return None;
            }
            angles[t] = Some(a);
        }
        let r = self.model.reangled(&angles).ok()?;
        Some(self.opened(&r))
    }

    /// The `+` tie of a set of tiers, in tier order.
    fn tie_key(&self, set: &BTreeSet<usize>) -> String {
        set.iter()
            .map(|&t| self.model.names[t].as_str())
            .collect::<Vec<_>>()
            .join("+")
    }

    /// Walk each free key (`key`, `lo`, `hi`) alone from its value in `start` (a completed set
    /// of values) to each bound, and say where the design stops being itself: the cut at that
    /// value cannot be built as this design (a facet vanishes, an edge appears or vanishes, a
    /// meet the space refuses opens). 16 steps a side, then bisection to 0.005°.
    pub fn breaches(
        &self,
        free: &[(String, f64, f64)],
        start: &BTreeMap<String, f64>,
    ) -> Vec<Breach> {
        let mut out = Vec::new();
        for (key, lo, hi) in free {
            let Some(&s) = start
                .get(key)
                .or(self.range(key).map(|r| r.default).as_ref())
            else {
                continue;
            };
            let fails = |v: f64| -> Option<String> {
                let mut values = start.clone();
                values.insert(key.clone(), v);
                self.build_at("probe", &values, false)
                    .err()
                    .map(|e| why(&e))
            };
            if let Some(what) = fails(s) {
                out.push(Breach {
                    key: key.clone(),
                    at: s,
                    holds: (s, s),
                    what,
                });
                continue;
            }
            let mut holds = (s, s);
            let mut first: Option<(f64, String)> = None;
            for (end, low) in [(*hi, false), (*lo, true)] {
                let mut ok = s;
                for k in 1..=STEPS {
                    let v = s + (end - s) * k as f64 / STEPS as f64;
                    let Some(mut what) = fails(v) else {
                        ok = v;
                        continue;
                    };
                    let mut bad = v;
                    while (bad - ok).abs() > RESOLUTION {
                        let mid = 0.5 * (ok + bad);
                        match fails(mid) {
                            Some(w) => {
                                bad = mid;
                                what = w;
                            }
                            None => ok = mid,
                        }
                    }
                    if first.is_none() {
                        first = Some((bad, what));
                    }
                    break;
                }
                if low {
                    holds.0 = ok;
                } else {
                    holds.1 = ok;
                }
            }
            if let Some((at, what)) = first {
                out.push(Breach {
                    key: key.clone(),
                    at,
                    holds,
                    what,
                });
            }
        }
        out
    }
}

/// What a failed build says, without the cut's name: `the edge vanishes between facets A and
/// B`, `these angles open the meet …`.
fn why(e: &Error) -> String {
    match e {
        Error::Invalid { message, .. } => message.clone(),
        other => {
            let t = other.to_string();
            match t.split_once("at these angles: ") {
                Some((_, rest)) => rest.to_string(),
                None => t
                    .strip_prefix("geometry: ")
                    .map(str::to_string)
                    .unwrap_or(t),
            }
        }
    }
}

/// Every `k`-subset of `0..n`, in lexicographic order.
fn combinations(n: usize, k: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut pick: Vec<usize> = (0..k).collect();
    if k == 0 || k > n {
        return out;
    }
    loop {
        out.push(pick.clone());
        let Some(i) = (0..k).rev().find(|&i| pick[i] < n - k + i) else {
            return out;
        };
        pick[i] += 1;
        for j in i + 1..k {
            pick[j] = pick[j - 1] + 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combinations_are_all_subsets_once() {
        assert_eq!(combinations(4, 2).len(), 6);
        assert_eq!(combinations(5, 3).len(), 10);
        assert_eq!(combinations(3, 3), vec![vec![0, 1, 2]]);
        assert!(combinations(2, 3).is_empty());
    }
}
