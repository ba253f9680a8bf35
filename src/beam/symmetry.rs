//! Symmetries of a solid about the z axis: finding the group from the facet planes, the wedge
//! a direction keeps, and handing each traced exit beam out once per symmetry.

use super::exit::ExitBeam;
use super::frame::Frame;
use super::sink::ExitSink;
use crate::geometry::clip2d;
use glam::{DMat3, DVec2, DVec3, DVec4};

/// A symmetry of the solid: an orthogonal map about the z axis and the facet permutation it
/// induces.
#[derive(Clone, Debug)]
pub(super) struct SymOp {
    m: DMat3,
    mirror: bool,
    /// A mirror's line azimuth (radians); 0 for a rotation.
    azimuth: f64,
    perm: Vec<u32>,
}

/// The symmetry group of a solid about the z axis: its rotations, then its mirrors.
#[derive(Clone, Debug)]
pub(super) struct Symmetry {
    /// The symmetries (identity first): rotations, then mirrors.
    ops: Vec<SymOp>,
    /// Order of the rotation group about z (1 = none).
    rot_order: usize,
    /// Azimuth (radians) of one mirror plane through the z axis, if any.
    mirror_az: Option<f64>,
}

/// Hands each exit beam of the traced wedge to the real sink once per symmetry, transformed.
pub(super) struct SymSink<'a, S: ExitSink> {
    inner: &'a mut S,
    ops: Vec<(u16, &'a SymOp, [f64; 4])>,
    foot: Vec<DVec2>,
    place: Vec<DVec3>,
}

impl<'a, S: ExitSink> SymSink<'a, S> {
    pub(super) fn new(
        symmetry: &'a Symmetry,
        group: &[usize],
        frame: &Frame,
        inner: &'a mut S,
    ) -> Self {
        let ops = group
            .iter()
            .map(|&i| {
                let op = &symmetry.ops[i];
                let (gu, gv) = (op.m * frame.u, op.m * frame.v);
                (
                    i as u16,
                    op,
                    [
                        gu.dot(frame.u),
                        gv.dot(frame.u),
                        gu.dot(frame.v),
                        gv.dot(frame.v),
                    ],
                )
            })
            .collect::<Vec<_>>();
        if ops.len() > 1 {
            let maps: Vec<(u16, [f64; 4])> = ops.iter().map(|&(i, _, m2)| (i, m2)).collect();
            inner.symmetries(&maps);
        }
        SymSink {
            inner,
            ops,
            foot: Vec::new(),
            place: Vec::new(),
        }
    }
}

impl<S: ExitSink> ExitSink for SymSink<'_, S> {
    fn wants_footprints(&self) -> bool {
        self.inner.wants_footprints()
    }
    fn wants_orbit(&self, e: &ExitBeam) -> bool {
        self.inner.wants_orbit(e)
    }
    fn wants_exit_places(&self) -> bool {
        self.inner.wants_exit_places()
    }
    fn wants_narrow_polygons(&self) -> bool {
        self.inner.wants_narrow_polygons()
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        self.exit_at(e, fp, &[]);
    }
    fn exit_at(&mut self, e: &ExitBeam, fp: &[DVec2], place: &[DVec3]) {
        if !self.inner.wants_orbit(e) {
            return;
        }
        for &(i, op, m2) in &self.ops {
            if i == 0 {
                self.inner.exit_at(e, fp, place);
                continue;
            }
            let mut stokes = e.stokes;
            if op.mirror {
                // A mirror turns the s–p frame's handedness: U and V change sign.
                stokes.z = -stokes.z;
                stokes.w = -stokes.w;
            }
            let t = ExitBeam {
                direction: op.m * e.direction,
                axis: op.m * e.axis,
                stokes,
                entry_facet: op.perm[e.entry_facet] as usize,
                exit_facet: op.perm[e.exit_facet] as usize,
                sym: i,
                ..*e
            };
            self.foot.clear();
            self.foot.extend(
                fp.iter()
                    .map(|p| DVec2::new(m2[0] * p.x + m2[1] * p.y, m2[2] * p.x + m2[3] * p.y)),
            );
            self.place.clear();
            if !place.is_empty() && self.inner.wants_exit_places() {
                self.place.extend(place.iter().map(|&x| op.m * x));
            }
            self.inner.exit_at(&t, &self.foot, &self.place);
        }
    }
}

/// Mirror across the vertical plane at azimuth `phi` (radians).
pub(crate) fn mirror_matrix(phi: f64) -> DMat3 {
    let m = DVec3::new(-phi.sin(), phi.cos(), 0.0);
    DMat3::IDENTITY - 2.0 * DMat3::from_cols(m * m.x, m * m.y, m * m.z)
}

/// The facet permutation of `m` if it maps every facet plane onto a facet plane.
fn facet_permutation(normals: &[DVec3], offsets: &[f64], m: &DMat3) -> Option<Vec<u32>> {
    let tol = 1e-9;
    let mut perm = Vec::with_capacity(normals.len());
    for (n, o) in normals.iter().zip(offsets) {
        let mn = *m * *n;
        let j = (0..normals.len()).find(|&j| {
            normals[j].distance_squared(mn) < tol * tol && (offsets[j] - o).abs() < tol
        })?;
        perm.push(j as u32);
    }
    Some(perm)
}
/// What a trace clips its root facets to: the symmetry's `wedge` (half-spaces through the
/// origin), a convex `window` (`n · x <= c` for each `(n, c)`), and the lit cross-section
/// `total` their shares are taken of (see [`clipped_share`]).
pub(super) struct RootClip<'a> {
    pub(super) wedge: &'a [DVec3],
    pub(super) window: &'a [DVec4],
    pub(super) total: f64,
}

/// The part of a root facet's polygon `cur` inside the symmetry's `wedge` (half-spaces
/// through the origin) and a convex `window` (`n · x <= c` for each `(n, c)`), clipped in
/// place (`piece` is scratch), and its share of the light: its footprint's area (`map` takes
/// a point to the traced frame's plane) over `total`. `full` (the whole facet's share) when
/// there is neither wedge nor window; `None` when nothing of the facet is left.
pub(super) fn clipped_share(
    cur: &mut Vec<DVec3>,
    wedge: &[DVec3],
    window: &[DVec4],
    piece: &mut Vec<DVec3>,
    map: impl Fn(DVec3) -> DVec2,
    total: f64,
    full: f64,
) -> Option<f64> {
    if wedge.is_empty() && window.is_empty() {
        return Some(full);
    }
    for h in wedge {
        clip_halfspace(cur, *h, piece);
        std::mem::swap(cur, piece);
        if cur.is_empty() {
            break;
        }
    }
    for h in window {
        if cur.is_empty() {
            break;
        }
        clip_halfspace_at(cur, h.truncate(), h.w, piece);
        std::mem::swap(cur, piece);
    }
    if cur.is_empty() {
        return None;
    }
    let fp: Vec<DVec2> = cur.iter().map(|&x| map(x)).collect();
    let p = clip2d::area(&fp) / total;
    (p > 0.0).then_some(p)
}

/// Clip a convex planar polygon by the half-space `n · x <= 0`.
pub(super) fn clip_halfspace(poly: &[DVec3], n: DVec3, out: &mut Vec<DVec3>) {
    clip_halfspace_at(poly, n, 0.0, out);
}

/// Clip a convex planar polygon by the half-space `n · x <= c`.
pub(super) fn clip_halfspace_at(poly: &[DVec3], n: DVec3, c: f64, out: &mut Vec<DVec3>) {
    out.clear();
    let k = poly.len();
    for i in 0..k {
        let (p, q) = (poly[i], poly[(i + 1) % k]);
        let (dp, dq) = (n.dot(p) - c, n.dot(q) - c);
        if dp <= 0.0 {
            out.push(p);
        }
        if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    if out.len() < 3 {
        out.clear();
    }
}

impl Symmetry {
    /// Find the rotations about the z axis and the mirrors through it that map the solid with
    /// facet planes `n · x = o` (`normals`, `offsets`) onto itself (the ones a face-up view
    /// shares).
    pub(super) fn find(normals: &[DVec3], offsets: &[f64]) -> Symmetry {
        let rot = |k: usize| DMat3::from_rotation_z(std::f64::consts::TAU / k as f64);
        let k = [64, 48, 32, 24, 16, 12, 10, 9, 8, 7, 6, 5, 4, 3, 2]
            .into_iter()
            .find(|&k| facet_permutation(normals, offsets, &rot(k)).is_some())
            .unwrap_or(1);
        // Mirror candidates: bisectors between a tilted facet's normal and its look-alikes.
        let mut mirror = None;
        if let Some(f0) = (0..normals.len()).find(|&f| normals[f].truncate().length() > 1e-6) {
            let a0 = normals[f0].y.atan2(normals[f0].x);
            for j in 0..normals.len() {
                if (normals[j].z - normals[f0].z).abs() < 1e-9
                    && (offsets[j] - offsets[f0]).abs() < 1e-9
                {
                    let aj = normals[j].y.atan2(normals[j].x);
                    let phi = 0.5 * (a0 + aj);
                    for cand in [phi, phi + std::f64::consts::FRAC_PI_2] {
                        if facet_permutation(normals, offsets, &mirror_matrix(cand)).is_some() {
                            mirror = Some(cand.rem_euclid(std::f64::consts::PI / k as f64));
                            break;
                        }
                    }
                }
                if mirror.is_some() {
                    break;
                }
            }
        }
        let mut ops = Vec::new();
        for j in 0..k {
            let m = DMat3::from_rotation_z(std::f64::consts::TAU * j as f64 / k as f64);
            if let Some(perm) = facet_permutation(normals, offsets, &m) {
                ops.push(SymOp {
                    m,
                    mirror: false,
                    azimuth: 0.0,
                    perm,
                });
            }
        }
        if let Some(phi0) = mirror {
            for j in 0..k {
                let azimuth = phi0 + std::f64::consts::PI * j as f64 / k as f64;
                let m = mirror_matrix(azimuth);
                if let Some(perm) = facet_permutation(normals, offsets, &m) {
                    ops.push(SymOp {
                        m,
                        mirror: true,
                        azimuth,
                        perm,
                    });
                }
            }
        }
        // Keep the symmetry only if the whole group was found consistently.
        if ops.len() == k * if mirror.is_some() { 2 } else { 1 } {
            Symmetry {
                ops,
                rot_order: k,
                mirror_az: mirror,
            }
        } else {
            Symmetry {
                ops: vec![SymOp {
                    m: DMat3::IDENTITY,
                    mirror: false,
                    azimuth: 0.0,
                    perm: (0..normals.len() as u32).collect(),
                }],
                rot_order: 1,
                mirror_az: None,
            }
        }
    }

    /// Facet permutation of symmetry `i` (for facet sequences of replicated exit beams).
    pub(super) fn permutation(&self, i: usize) -> &[u32] {
        &self.ops[i].perm
    }

    /// Number of symmetries (1 = none; 16 for a round brilliant).
    pub(super) fn order(&self) -> usize {
        self.ops.len()
    }

    /// The order of the rotation group (1 = none) and the azimuth of one mirror line, if any.
    pub(super) fn rotations_and_mirror(&self) -> (usize, Option<f64>) {
        (self.rot_order, self.mirror_az)
    }

    /// [`Symmetry::rotations_and_mirror`] of the subgroup that maps `axis` onto itself or its
    /// opposite: its rotations are a cyclic group (order `k'`) and its mirrors, if any, the
    /// mirrors `β' + jπ/k'` of that group.
    pub(super) fn rotations_and_mirror_keeping(&self, axis: DVec3) -> (usize, Option<f64>) {
        let keeps = |op: &&SymOp| {
            let m = op.m * axis;
            (m - axis).length() < 1e-9 || (m + axis).length() < 1e-9
        };
        let kept: Vec<&SymOp> = self.ops.iter().filter(keeps).collect();
        let k = kept.iter().filter(|op| !op.mirror).count().max(1);
        let mirror = kept
            .iter()
            .find(|op| op.mirror)
            .map(|op| op.azimuth.rem_euclid(std::f64::consts::PI / k as f64));
        (k, mirror)
    }

    /// The symmetries that fix direction `d` (indices into `ops`), and the half-spaces
    /// `n · x <= 0` (planes through the z axis) cutting out a fundamental wedge whose images
    /// under them tile space.
    pub(super) fn frame_symmetry(&self, d: DVec3) -> (Vec<usize>, Vec<DVec3>) {
        use std::f64::consts::{PI, TAU};
        let k = self.rot_order;
        let side = |a: f64| DVec3::new(a.sin(), -a.cos(), 0.0); // n·x <= 0: left of azimuth a
        if d.truncate().length() < 1e-12 {
            let all: Vec<usize> = (0..self.ops.len()).collect();
            let wedge = match self.mirror_az {
                Some(p0) if k == 1 => vec![side(p0)],
                Some(p0) => vec![side(p0), -side(p0 + PI / k as f64)],
                None if k == 1 => vec![],
                None if k == 2 => vec![side(0.0)],
                None => vec![side(0.0), -side(TAU / k as f64)],
            };
            return (all, wedge);
        }
        // A tilted direction keeps at most the mirror through it.
        let psi = d.y.atan2(d.x);
        if let Some(p0) = self.mirror_az {
            let step = PI / k as f64;
            let x = (psi - p0) / step;
            if (x - x.round()).abs() < 1e-9 {
                let j = (x.round() as i64).rem_euclid(k as i64) as usize;
                let idx = k + j;
                if idx < self.ops.len() && self.ops[idx].mirror {
                    return (vec![0, idx], vec![side(psi)]);
                }
            }
        }
        (vec![0], vec![])
    }

    /// [`Symmetry::frame_symmetry`] for a birefringent stone with optic axis `axis`: only the
    /// symmetries that also map the axis onto itself (or its opposite: a uniaxial crystal is
    /// the same either way) are kept, with a fundamental wedge of the group they form — for
    /// an axis along z all of them, for a tilted one at most the half-turn and the mirrors
    /// through and across the axis's azimuth.
    pub(super) fn frame_symmetry_keeping(&self, d: DVec3, axis: DVec3) -> (Vec<usize>, Vec<DVec3>) {
        use std::f64::consts::{FRAC_PI_2, PI};
        let (group, wedge) = self.frame_symmetry(d);
        let keeps = |i: usize| {
            let m = self.ops[i].m * axis;
            (m - axis).length() < 1e-9 || (m + axis).length() < 1e-9
        };
        if group.iter().all(|&i| keeps(i)) {
            return (group, wedge);
        }
        let sub: Vec<usize> = group.into_iter().filter(|&i| keeps(i)).collect();
        let side = |a: f64| DVec3::new(a.sin(), -a.cos(), 0.0);
        let mirrors: Vec<f64> = sub
            .iter()
            .filter(|&&i| self.ops[i].mirror)
            .map(|&i| self.ops[i].azimuth.rem_euclid(PI))
            .collect();
        let half_turn = sub.iter().any(|&i| i != 0 && !self.ops[i].mirror);
        let wedge = match (half_turn, mirrors.as_slice()) {
            (false, []) => vec![],
            (false, [a]) => vec![side(*a)],
            (true, []) if sub.len() == 2 => vec![side(0.0)],
            (true, [a, b]) if sub.len() == 4 => {
                let a = a.min(*b);
                vec![side(a), -side(a + FRAC_PI_2)]
            }
            _ => return (vec![0], vec![]),
        };
        (sub, wedge)
    }
}
