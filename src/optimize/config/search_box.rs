//! The box a search moves in: the free parameters (bounds and start) and the space that builds
//! the cut at a point of it, every other parameter held at the start.

use super::free::{FreeParam, OPTIC_AXIS};
use crate::cut::{Cut, CutSpace};
use crate::error::Result;
use std::collections::BTreeMap;

/// The box a search moves in, borrowed from a [`Config`](super::Config)
/// ([`Config::search_box`](super::Config::search_box)): a point is one value per free
/// parameter, in [`SearchBox::free`]'s order.
#[derive(Clone, Copy, Debug)]
pub struct SearchBox<'a> {
    /// The cut's name (the config's).
    pub name: &'a str,
    /// The space that builds the cuts.
    pub space: &'a dyn CutSpace,
    /// Every parameter of the space at its start value; the fixed ones stay there.
    pub start: &'a BTreeMap<String, f64>,
    /// The free parameters: the box's axes, in order.
    pub free: &'a [FreeParam],
}

impl SearchBox<'_> {
    /// The cut of the space with parameters `params` (the free ones included): a free
    /// `optic_axis` is not the space's, and rides along in the cut's [`params`](Cut::params),
    /// where the evaluators read it.
    pub fn build(&self, label: &str, params: &BTreeMap<String, f64>) -> Result<Cut> {
        match params.get(OPTIC_AXIS) {
            None => self.space.build(label, params),
            Some(&axis) => {
                let mut p = params.clone();
                p.remove(OPTIC_AXIS);
                let mut cut = self.space.build(label, &p)?;
                cut.params.insert(OPTIC_AXIS.to_string(), axis);
                Ok(cut)
            }
        }
    }

    /// The space's parameters with the free ones set to `x`.
    pub fn params_at(&self, x: &[f64]) -> BTreeMap<String, f64> {
        let mut p = self.start.clone();
        for (f, v) in self.free.iter().zip(x) {
            p.insert(f.key.clone(), *v);
        }
        p
    }

    /// The cut at the point `x`, named as the config's.
    pub fn cut_at(&self, x: &[f64]) -> Result<Cut> {
        self.build(self.name, &self.params_at(x))
    }

    /// The free parameters' start values: the start point.
    pub fn start_x(&self) -> Vec<f64> {
        self.free.iter().map(|f| f.start).collect()
    }

    /// The point `x` in the unit box (0 at each lower bound, 1 at each upper).
    pub fn unit_of(&self, x: &[f64]) -> Vec<f64> {
        self.free
            .iter()
            .zip(x)
            .map(|(f, v)| f.unit_of(*v))
            .collect()
    }

    /// The free parameters' keys, in order.
    pub fn keys(&self) -> Vec<String> {
        self.free.iter().map(|f| f.key.clone()).collect()
    }
}
