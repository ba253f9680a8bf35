//! The planes between a layout's stones, and laser layouts: stones parted pair by pair by a
//! kerf-wide gap along a plane cut only between them, not through the whole piece.
//!
//! A laser layout starts from the sawn layout (a sawn layout is a laser layout: its saw cuts
//! part every pair) and improves it stone by stone (coordinate ascent, at most [`ROUNDS`]
//! rounds): stone `i`'s **cell** is the rough cut by one wall per other stone `j`, the plane
//! tangent to `j` moved out by the allowance and the kerf (`n·x >= max_j n·v + allowance +
//! kerf`), its normal `n` chosen among the current wall's, the normals of `j`'s facets, the
//! reversed normals of `i`'s facets and the line between their centres as the one that
//! leaves the largest copy of stone `i` at its own orientation (the exact program of
//! [`super::super::fit`]), the walls taken nearest stone first; the stone is then searched
//! in full in its cell (the allowance, the inclusions and the objective as a sawn piece's)
//! and kept when it is worth more. Every pair stays parted: a re-placed stone lies beyond its
//! walls, which are tangent to the stones left where they were. While the layout holds fewer
//! stones than asked, each round also tries a new stone in a cell walled off every stone
//! (the proxy a regular icosahedron). A greedy heuristic, not an optimum.

use super::solids::widest;
use super::{Effort, Layout, LayoutPlanner, Piece, SawCut, Stone, PROXY};
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane, Plane, Polyhedron};
use crate::plan::config::Cutter;

/// Rounds of the laser's coordinate ascent.
const ROUNDS: usize = 3;

/// A plane between two stones of a layout (indices into [`Layout::stones`]): the kerf's
/// middle plane `normal·x = offset` (mm, the rough's coordinates), the first stone on the side
/// `normal·x <= offset − kerf/2 − allowance`, the second on `normal·x >= offset + kerf/2 +
/// allowance`.
#[derive(Clone, Debug, PartialEq)]
pub struct Parting {
    /// The two stones, the first below the plane.
    pub stones: [usize; 2],
    /// Unit normal, from the first stone towards the second.
    pub normal: DVec3,
    /// Offset (mm).
    pub offset: f64,
}

/// The planes between a sawn layout's stones: for each pair, the saw cut that parted their
/// pieces (the cut of the pieces' last common piece).
pub(super) fn sawn_pairs(stones: &[Stone], saw: &[SawCut]) -> Vec<Parting> {
    let mut out = Vec::new();
    for a in 0..stones.len() {
        for b in a + 1..stones.len() {
            let (p, q) = (stones[a].piece.as_bytes(), stones[b].piece.as_bytes());
            let k = p.iter().zip(q).take_while(|(x, y)| x == y).count();
            let parent = if k == 0 {
                "rough"
            } else {
                &stones[a].piece[..k]
            };
            let Some(cut) = saw.iter().find(|c| c.piece == parent) else {
                continue;
            };
            // The side normal·x < offset is labelled `A` (the first cut) or `a`.
            let s = if p.get(k).is_some_and(|c| c.eq_ignore_ascii_case(&b'a')) {
                1.0
            } else {
                -1.0
            };
            out.push(Parting {
                stones: [a, b],
                normal: s * cut.normal,
                offset: s * cut.offset,
            });
        }
    }
    out
}

/// The mean of a stone's placed vertices.
fn centre(v: &[DVec3]) -> DVec3 {
    v.iter().copied().sum::<DVec3>() / v.len().max(1) as f64
}

/// The volume of the half-spaces `planes` (0 when empty).
fn volume_of(planes: &[FacetPlane]) -> f64 {
    Polyhedron::from_planes_pruned(planes).map_or(0.0, |p| p.volume())
}

impl LayoutPlanner<'_> {
    /// The laser layout grown from the sawn layout `sawn` (see the module documentation).
    pub(super) fn laser(&self, sawn: Layout) -> Result<Layout> {
        let mut stones = sawn.stones;
        let mut pairs = sawn.pairs;
        for _ in 0..ROUNDS {
            let mut better = false;
            for i in 0..stones.len() {
                self.slide(i, &mut stones, &pairs);
            }
            for i in 0..stones.len() {
                if let Some((st, walls)) = self.regrow(i, &stones, &pairs) {
                    if st.plan.objective > stones[i].plan.objective * (1.0 + 1e-9) {
                        stones[i] = st;
                        pairs.retain(|p| !p.stones.contains(&i));
                        pairs.extend(walls);
                        better = true;
                    }
                }
            }
            if stones.len() < self.config.stones {
                if let Some((st, walls)) = self.regrow(stones.len(), &stones, &pairs) {
                    stones.push(st);
                    pairs.extend(walls);
                    better = true;
                }
            }
            if self.stopped() {
                return Err(Error::invalid("plan", "interrupted"));
            }
            if !better {
                break;
            }
        }
        pairs.sort_by_key(|p| p.stones);
        for (k, s) in stones.iter_mut().enumerate() {
            s.piece = format!("cell-{}", k + 1);
            if let Ok(cell) = Polyhedron::from_planes_pruned(&self.cell(k, &pairs, None)) {
                s.piece_solid = cell;
            }
        }
        let cuts = pairs.iter().map(|p| self.wall(p, &pairs)).collect();
        let mut layout = self.layout_of(stones, cuts)?;
        layout.cutter = Cutter::Laser;
        layout.pairs = pairs;
        Ok(layout)
    }

    /// Slide stone `i` away from the others as far as its walls, the rough (less the
    /// allowance) and its inclusions' keep-off planes let it (a few straight moves, each along
    /// the away direction less its part into the planes met): a stone as large as its room
    /// allows (a slab's thickness) sits anywhere its program put it, and moved into its
    /// corner it leaves the others room to grow. Its weight does not change.
    fn slide(&self, i: usize, stones: &mut [Stone], pairs: &[Parting]) {
        if stones.len() < 2 || !stones[i].holds.is_empty() {
            return;
        }
        let half = 0.5 * self.config.kerf_mm + self.config.allowance_mm;
        let mut planes: Vec<Plane> = self
            .rough
            .solid
            .facets()
            .iter()
            .map(|f| Plane {
                normal: f.plane.normal,
                offset: f.plane.offset - self.config.allowance_mm,
            })
            .collect();
        for p in pairs {
            if p.stones[0] == i {
                planes.push(Plane {
                    normal: p.normal,
                    offset: p.offset - half,
                });
            } else if p.stones[1] == i {
                planes.push(Plane {
                    normal: -p.normal,
                    offset: -(p.offset + half),
                });
            }
        }
        planes.extend(stones[i].separations.iter().map(|(_, h)| *h));
        let mut v = stones[i].plan.placed_vertices();
        let c = centre(&v);
        let mut u = DVec3::ZERO;
        for (j, s) in stones.iter().enumerate() {
            if j != i {
                let d = c - centre(&s.plan.placed_vertices());
                u += d / d.length_squared().max(1e-12);
            }
        }
        let mut moved = DVec3::ZERO;
        for _ in 0..4 {
            if u.length() < 1e-9 {
                break;
            }
            u = u.normalize();
            let mut step = f64::INFINITY;
            let mut hit = Vec::new();
            for p in &planes {
                let along = p.normal.dot(u);
                if along > 1e-9 {
                    let slack = p.offset
                        - v.iter()
                            .map(|x| p.normal.dot(*x))
                            .fold(f64::NEG_INFINITY, f64::max);
                    let t = slack.max(0.0) / along;
                    if t < step - 1e-12 {
                        step = t;
                        hit = vec![p.normal];
                    } else if t <= step + 1e-12 {
                        hit.push(p.normal);
                    }
                }
            }
            if !step.is_finite() {
                break;
            }
            // Stop just short of the plane met (no rounding past it).
            let go = (step - 1e-9).max(0.0) * u;
            v.iter_mut().for_each(|x| *x += go);
            moved += go;
            for n in hit {
                u -= u.dot(n) * n;
            }
        }
        stones[i].plan.shift += moved;
    }

    /// The half-spaces of stone `k`'s cell: the rough's and, for each of `pairs` with `k`
    /// but `except`, the kerf's face on `k`'s side.
    fn cell(&self, k: usize, pairs: &[Parting], except: Option<&Parting>) -> Vec<FacetPlane> {
        let half = 0.5 * self.config.kerf_mm;
        let mut planes = self.rough.solid.facet_planes();
        for p in pairs {
            if except == Some(p) {
                continue;
            }
            let name = format!("laser-{}-{}", p.stones[0] + 1, p.stones[1] + 1);
            if p.stones[0] == k {
                planes.push(FacetPlane::new(p.normal, p.offset - half, name, "laser"));
            } else if p.stones[1] == k {
                planes.push(FacetPlane::new(
                    -p.normal,
                    -(p.offset + half),
                    name,
                    "laser",
                ));
            }
        }
        planes
    }

    /// The laser cut of `pair`: the region its wall parts (the rough within both stones'
    /// other walls) and the kerf's slab in it.
    fn wall(&self, pair: &Parting, pairs: &[Parting]) -> SawCut {
        let [a, b] = pair.stones;
        let mut planes = self.cell(a, pairs, Some(pair));
        planes.extend(
            self.cell(b, pairs, Some(pair))
                .into_iter()
                .skip(self.rough.solid.facets().len()),
        );
        let half = 0.5 * self.config.kerf_mm;
        let side = |n: DVec3, d: f64| {
            let mut with = planes.clone();
            with.push(FacetPlane::new(n, d, "kerf", "laser"));
            volume_of(&with)
        };
        let region =
            Polyhedron::from_planes_pruned(&planes).unwrap_or_else(|_| self.rough.solid.clone());
        let loss = region.volume()
            - side(pair.normal, pair.offset - half)
            - side(-pair.normal, -(pair.offset + half));
        SawCut {
            piece: format!("cell-{}/cell-{}", a + 1, b + 1),
            normal: pair.normal,
            offset: pair.offset,
            kerf_loss_mm3: loss.max(0.0),
            piece_solid: region,
        }
    }

    /// Stone `i` (or a new stone when `i` is past the last) searched in a cell walled off
    /// every other stone, with its walls; `None` when no stone fits.
    fn regrow(
        &self,
        i: usize,
        stones: &[Stone],
        pairs: &[Parting],
    ) -> Option<(Stone, Vec<Parting>)> {
        let gap = self.config.kerf_mm + self.config.allowance_mm;
        let half = 0.5 * self.config.kerf_mm;
        let own: Option<Vec<DVec3>> = stones.get(i).map(|s| s.plan.placed_vertices());
        let (proxy, ci) = match &own {
            Some(v) => {
                let c = centre(v);
                (v.iter().map(|p| *p - c).collect::<Vec<_>>(), Some(c))
            }
            None => (PROXY.iter().map(|p| DVec3::from_array(*p)).collect(), None),
        };
        let placed: Vec<Vec<DVec3>> = stones.iter().map(|s| s.plan.placed_vertices()).collect();
        let mut others: Vec<usize> = (0..stones.len()).filter(|&j| j != i).collect();
        if let Some(c) = ci {
            others.sort_by(|&x, &y| {
                centre(&placed[x])
                    .distance(c)
                    .total_cmp(&centre(&placed[y]).distance(c))
                    .then(x.cmp(&y))
            });
        }
        let mut region = self.rough.solid.clone();
        let mut walls = Vec::new();
        for j in others {
            let vj = &placed[j];
            let cj = centre(vj);
            // Normals from stone j towards stone i.
            let mut normals: Vec<DVec3> = Vec::new();
            for p in pairs {
                if p.stones == [j, i] {
                    normals.push(p.normal);
                } else if p.stones == [i, j] {
                    normals.push(-p.normal);
                }
            }
            if let Some(c) = ci {
                if c.distance(cj) > 1e-12 {
                    normals.push((c - cj).normalize());
                }
                normals.extend(
                    stones[i]
                        .plan
                        .placed_planes()
                        .iter()
                        .map(|f| -f.plane.normal),
                );
            }
            normals.extend(
                stones[j]
                    .plan
                    .placed_planes()
                    .iter()
                    .map(|f| f.plane.normal),
            );
            let sides: Vec<Plane> = normals
                .iter()
                .map(|n| {
                    let h = vj
                        .iter()
                        .map(|v| n.dot(*v))
                        .fold(f64::NEG_INFINITY, f64::max);
                    Plane {
                        normal: -*n,
                        offset: -(h + gap),
                    }
                })
                .collect();
            let (_, h) = widest(&region, &sides, &proxy)?;
            let mut fps = region.facet_planes();
            fps.push(FacetPlane {
                plane: h,
                name: format!("laser-{}", j + 1),
                tier: "laser".into(),
            });
            region = Polyhedron::from_planes_pruned(&fps).ok()?;
            // The kerf's middle plane: the cell's face moved back by half the kerf.
            let (n, mid) = (-h.normal, -h.offset - half);
            walls.push(if j < i {
                Parting {
                    stones: [j, i],
                    normal: n,
                    offset: mid,
                }
            } else {
                Parting {
                    stones: [i, j],
                    normal: -n,
                    offset: -mid,
                }
            });
        }
        let piece = Piece {
            label: format!("cell-{}", i + 1),
            solid: region,
        };
        let st = self.stone(&piece, Effort::Full)?;
        Some((st, walls))
    }
}
