//! [`BeamTree`]: everything one trace produced (exit beams, power accounting, footprints), and
//! the traces that collect it ([`Stone::trace`], [`Stone::trace_medium`], [`trace()`]).

use super::crystal::Medium;
use super::exit::ExitBeam;
use super::frame::Frame;
use super::options::TraceOptions;
use super::sink::{ExitSink, TraceStats};
use super::stone::Stone;
use crate::geometry::Polyhedron;
use crate::optics::Material;
use glam::DVec2;

/// Everything one trace produced: exit beams, power accounting, footprints.
#[derive(Clone, Debug)]
pub struct BeamTree {
    /// The incoming direction and image axes.
    pub frame: Frame,
    /// Refractive index used (a birefringent stone's ordinary index).
    pub ri: f64,
    /// The medium traced (its indices, optic axis and per-mode absorption).
    pub medium: Medium,
    /// Wavelength in nm (as given; informative when the index was fixed).
    pub wavelength_nm: f64,
    /// Whether polarization was tracked.
    pub polarization: bool,
    /// Power accounting and work done.
    pub stats: TraceStats,
    /// Every exit beam, in tracing order.
    pub exits: Vec<ExitBeam>,
    nodes: Vec<(u32, u32)>,
    perms: Vec<Vec<u32>>,
    pub(super) footprints: Vec<DVec2>,
    footprint_ranges: Vec<(u32, u32)>,
}

impl BeamTree {
    /// Total power of the exit beams.
    pub fn power_out(&self) -> f64 {
        self.exits.iter().map(|e| e.power).sum()
    }

    /// `power_in − power_out − cut_off − absorbed`: zero to rounding.
    pub fn balance(&self) -> f64 {
        self.stats.power_in - self.power_out() - self.stats.cut_off - self.stats.absorbed
    }

    /// Facet indices the beam met, from the entry facet to the exit facet.
    pub fn sequence(&self, e: &ExitBeam) -> Vec<usize> {
        let mut out = Vec::new();
        let mut k = e.node;
        while k != u32::MAX {
            let (parent, facet) = self.nodes[k as usize];
            out.push(facet as usize);
            k = parent;
        }
        out.reverse();
        if e.sym != 0 {
            if let Some(p) = self.perms.get(e.sym as usize) {
                for f in &mut out {
                    *f = p[*f] as usize;
                }
            }
        }
        out
    }

    /// Footprint of exit beam number `i` (an index into [`BeamTree::exits`]) in the frame's image
    /// coordinates; empty unless traced with [`TraceOptions::footprints`].
    pub fn footprint(&self, i: usize) -> &[DVec2] {
        match self.footprint_ranges.get(i) {
            Some(&(a, b)) => &self.footprints[a as usize..b as usize],
            None => &[],
        }
    }
}

struct Collect {
    exits: Vec<ExitBeam>,
    footprints: Vec<DVec2>,
    ranges: Vec<(u32, u32)>,
    want: bool,
}

impl ExitSink for Collect {
    fn wants_footprints(&self) -> bool {
        self.want
    }
    fn exit(&mut self, beam: &ExitBeam, footprint: &[DVec2]) {
        self.exits.push(*beam);
        if self.want {
            let a = self.footprints.len() as u32;
            self.footprints.extend_from_slice(footprint);
            self.ranges.push((a, self.footprints.len() as u32));
        }
    }
}

impl Stone {
    /// Trace one direction at one refractive index and collect the whole result.
    pub fn trace(
        &self,
        frame: &Frame,
        ri: f64,
        wavelength_nm: f64,
        opts: &TraceOptions,
    ) -> BeamTree {
        self.trace_medium(frame, &Medium::Isotropic(ri), wavelength_nm, opts)
    }

    /// Trace one direction through `medium` (singly refractive, or a birefringent crystal)
    /// and collect the whole result.
    pub fn trace_medium(
        &self,
        frame: &Frame,
        medium: &Medium,
        wavelength_nm: f64,
        opts: &TraceOptions,
    ) -> BeamTree {
        let mut sink = Collect {
            exits: Vec::new(),
            footprints: Vec::new(),
            ranges: Vec::new(),
            want: opts.footprints,
        };
        let (stats, nodes) = self.trace_medium_into(frame, medium, opts, &mut sink, true);
        let perms = (0..self.symmetry_order())
            .map(|i| self.permutation(i).to_vec())
            .collect();
        BeamTree {
            perms,
            frame: *frame,
            ri: medium.ri(),
            medium: *medium,
            wavelength_nm,
            polarization: opts.polarization,
            stats,
            exits: sink.exits,
            nodes,
            footprints: sink.footprints,
            footprint_ranges: sink.ranges,
        }
    }
}

/// Trace `solid` made of `material` at `wavelength_nm` for light arriving as `frame` says.
/// Convenience over [`Stone::new`] + [`Stone::trace`]; prepare a [`Stone`] once when tracing
/// many directions.
pub fn trace(
    solid: &Polyhedron,
    frame: &Frame,
    material: &Material,
    wavelength_nm: f64,
    opts: &TraceOptions,
) -> BeamTree {
    Stone::new(solid).trace(frame, material.ri(wavelength_nm), wavelength_nm, opts)
}
