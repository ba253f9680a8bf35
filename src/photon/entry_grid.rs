//! A directed light's entry test with a grid over the light square (see [`EntryGrid`]'s notes).

use super::solid::TraceSolid;
use crate::geometry::DVec3;

/// A directed light's entry test, precomputed: for the photon leaving the light at
/// `centre + a·u + b·v`, facet i's plane is met at `t_i = c0_i + a·cu_i + b·cv_i`. The photon
/// enters through the facet with the largest `t` among those facing the light if that is no
/// larger than the smallest `t` among those facing away, and it is inside every facet
/// parallel to the beam (`g0 − a·gu − b·gv ≥ 0`).
///
/// A grid of cells over the light square speeds this up: a cell no front facet's projected
/// bounding box touches is outside the stone's shadow; a cell whose four corners are inside
/// the (convex) shadow is wholly inside, and there the entry facet is the best of the few
/// front facets whose projected bounding boxes touch the cell. Only cells on the shadow's
/// border run the full test.
pub(super) struct EntryGrid {
    front: [Vec<f64>; 3],
    front_facet: Vec<usize>,
    back: [Vec<f64>; 3],
    parallel: Vec<[f64; 3]>,
    half: f64,
    /// Cells per unit of `a` and `b`: `GRID / (2 half)`.
    scale: f64,
    /// Each cell packed in 4 bytes (the grid then mostly stays in cache): [`MISS`],
    /// [`BORDER`], or an inside cell's candidates `start | len << 24`; row-major in (a, b).
    cells: Box<[u32; GRID * GRID]>,
    candidates: Vec<u32>,
}

/// A cell outside the shadow.
const MISS: u32 = u32::MAX;
/// A cell on the shadow's border (or an inside cell too big to pack: the full test is exact
/// everywhere).
const BORDER: u32 = u32::MAX - 1;

const BL: usize = 4;
/// Cells per side of the entry grid.
const GRID: usize = 128;

impl EntryGrid {
    pub(super) fn new(
        s: &TraceSolid,
        centre: DVec3,
        axis: DVec3,
        u: DVec3,
        v: DVec3,
        half: f64,
    ) -> EntryGrid {
        let mut front: [Vec<f64>; 3] = Default::default();
        let mut back: [Vec<f64>; 3] = Default::default();
        let mut front_facet = Vec::new();
        let mut parallel = Vec::new();
        for (i, n) in s.normals.iter().enumerate() {
            let nd = n.dot(axis);
            let g0 = s.off[i] - n.dot(centre);
            let (gu, gv) = (n.dot(u), n.dot(v));
            if nd.abs() < 1e-12 {
                parallel.push([g0, gu, gv]);
                continue;
            }
            let c = [g0 / nd, -gu / nd, -gv / nd];
            let dst = if nd < 0.0 { &mut front } else { &mut back };
            for k in 0..3 {
                dst[k].push(c[k]);
            }
            if nd < 0.0 {
                front_facet.push(i);
            }
        }
        let n_front = front_facet.len();
        // Pad to whole lanes with planes that never decide anything.
        while !front[0].len().is_multiple_of(BL) {
            front[0].push(f64::NEG_INFINITY);
            front[1].push(0.0);
            front[2].push(0.0);
            front_facet.push(usize::MAX);
        }
        while !back[0].len().is_multiple_of(BL) {
            back[0].push(f64::INFINITY);
            back[1].push(0.0);
            back[2].push(0.0);
        }
        let mut grid = EntryGrid {
            front,
            front_facet,
            back,
            parallel,
            half,
            scale: GRID as f64 / (2.0 * half),
            cells: Box::new([MISS; GRID * GRID]),
            candidates: Vec::new(),
        };
        // The grid.
        let step = 2.0 * half / GRID as f64;
        let corner = |i: usize| -half + i as f64 * step;
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); GRID * GRID];
        for (k, &f) in grid.front_facet[..n_front].iter().enumerate() {
            let (mut alo, mut ahi, mut blo, mut bhi) = (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            );
            for &vi in &s.facet_vertices[f] {
                let r = s.vertices[vi] - centre;
                let (a, b) = (r.dot(u), r.dot(v));
                alo = alo.min(a);
                ahi = ahi.max(a);
                blo = blo.min(b);
                bhi = bhi.max(b);
            }
            let pad = 1e-9 * (1.0 + half);
            let cell = |x: f64| (((x + half) / step).floor().max(0.0) as usize).min(GRID - 1);
            if ahi < -half - pad || alo > half + pad || bhi < -half - pad || blo > half + pad {
                continue;
            }
            for i in cell(alo - pad)..=cell(ahi + pad) {
                for j in cell(blo - pad)..=cell(bhi + pad) {
                    lists[i * GRID + j].push(k as u32);
                }
            }
        }
        let inside: Vec<bool> = (0..(GRID + 1) * (GRID + 1))
            .map(|c| {
                grid.entry_full(corner(c / (GRID + 1)), corner(c % (GRID + 1)))
                    .is_some()
            })
            .collect();
        for (c, list) in lists.iter().enumerate() {
            let (i, j) = (c / GRID, c % GRID);
            let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)];
            let start = grid.candidates.len();
            let cell = if list.is_empty() {
                MISS
            } else if corners.iter().all(|&(x, y)| inside[x * (GRID + 1) + y])
                && list.len() < 255
                && start + list.len() < 1 << 24
            {
                grid.candidates.extend_from_slice(list);
                start as u32 | (list.len() as u32) << 24
            } else {
                BORDER
            };
            grid.cells[c] = cell;
        }
        grid
    }

    /// The entry facet of the photon at (a, b), or `None` if it misses.
    ///
    /// The cell is found by a multiplication, which may round a point within an ulp or so of
    /// a cell's side into its neighbour: that changes nothing, as the cell only chooses the
    /// test. A miss cell is at least the bounding boxes' padding (1e-9) from every front
    /// facet's shadow, and an inside cell's candidates are every front facet whose padded
    /// box touches it, so both answer exactly for points that near them.
    #[inline(always)]
    pub(super) fn entry(&self, a: f64, b: f64) -> Option<usize> {
        let cell = |x: f64| grid_cell((x + self.half) * self.scale, GRID);
        match self.cells[cell(a) * GRID + cell(b)] {
            MISS => None,
            BORDER => self.entry_full(a, b),
            cell => {
                let (start, len) = ((cell & 0xFF_FFFF) as usize, (cell >> 24) as usize);
                let f = &self.front;
                let mut best = (f64::NEG_INFINITY, usize::MAX);
                for &k in &self.candidates[start..start + len] {
                    let k = k as usize;
                    let t = f[0][k] + a * f[1][k] + b * f[2][k];
                    if t > best.0 {
                        best = (t, k);
                    }
                }
                Some(self.front_facet[best.1])
            }
        }
    }

    /// The full entry test (every facet).
    #[inline(always)]
    pub(super) fn entry_full(&self, a: f64, b: f64) -> Option<usize> {
        let mut tin = [f64::NEG_INFINITY; BL];
        let mut fin = [0usize; BL];
        let f = &self.front;
        for c in (0..f[0].len()).step_by(BL) {
            for l in 0..BL {
                let i = c + l;
                let t = f[0][i] + a * f[1][i] + b * f[2][i];
                if t > tin[l] {
                    tin[l] = t;
                    fin[l] = i;
                }
            }
        }
        let mut tout = [f64::INFINITY; BL];
        let k = &self.back;
        for c in (0..k[0].len()).step_by(BL) {
            for (l, o) in tout.iter_mut().enumerate() {
                let i = c + l;
                let t = k[0][i] + a * k[1][i] + b * k[2][i];
                *o = if t < *o { t } else { *o };
            }
        }
        let (mut t_in, mut f_in) = (tin[0], fin[0]);
        for l in 1..BL {
            if tin[l] > t_in || (tin[l] == t_in && fin[l] < f_in) {
                t_in = tin[l];
                f_in = fin[l];
            }
        }
        let t_out = tout.iter().copied().fold(f64::INFINITY, f64::min);
        if t_in > t_out
            || self
                .parallel
                .iter()
                .any(|g| g[0] - a * g[1] - b * g[2] < 0.0)
        {
            return None;
        }
        let facet = self.front_facet[f_in];
        (facet != usize::MAX).then_some(facet)
    }
}

/// The cell of a grid of `cells` cells that `x` (in cell units from the grid's edge) falls
/// in; points on or past the edges (and NaN) fall in the edge cells. The photon kernel's
/// lookups (entry grid, sure-miss cells, exit-angle cells) find their cells with it: `as i32`
/// converts in one instruction and a check, where `as usize` needs more on x86.
#[inline(always)]
pub(super) fn grid_cell(x: f64, cells: usize) -> usize {
    (x as i32).clamp(0, cells as i32 - 1) as usize
}
