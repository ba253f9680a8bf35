//! Several stones in one rough (issue 54, `facetlab plan --stones N`): a layout of sawn
//! pieces, one cut in each, ranked by total value (or weight), with the saw's kerf, a
//! polishing allowance per stone and inclusions kept out.
//!
//! The design (sequential sawing on the exact containment of [`super::fit`]):
//!
//! - a **piece** is the rough cut by the saw planes so far, as half-spaces; a saw cut along
//!   the plane `u·x = c` splits a piece into `u·x <= c − kerf/2` and `u·x >= c + kerf/2` (the
//!   kerf's slab is lost, [`Layout::kerf_loss_mm3`]);
//! - a piece's **stone** lies in the piece's half-spaces each moved in by the allowance (every
//!   point of the stone at least the allowance from the piece's faces, sawn or natural: the
//!   inner parallel body of a convex piece, exact) and outside every inclusion grown by its
//!   margin: an inclusion that the piece still holds is kept out by one more half-space, the
//!   far side of one face of its grown hull ([`Inclusion::grown`]), chosen per inclusion in
//!   turn as the one that leaves the largest ball-like proxy (a regular icosahedron) inside. So each
//!   stone's containment stays the exact program of [`super::fit`] over the piece's planes
//!   (its polyhedron inside, not its bounding box), searched over orientation and
//!   proportions by the single-stone [`Planner`] treating the region as a rough. With a price
//!   table whose `included` factor is set, a stone may instead keep the inclusions inside,
//!   its value times that factor; the better of the two is kept;
//! - the **saw plan** is grown greedily: for every piece, every direction of [`directions`]
//!   (13 in the rough's principal frame: its axes, their face and body diagonals) and of the
//!   normals of the rough's 6 largest faces and the directions to its 6 farthest corners
//!   (with those tied with them), and
//!   `saw_offsets` offsets across the piece, the two halves' best stones are found by a short
//!   search (two starts, each restarted once, in each half's room cut from the piece's by
//!   one clip: [`Polyhedron::cut_by`]); the best 4 cuts (of different pieces or directions) are refined
//!   (the offset by golden section, the direction by tilts of 12°, 6°, 3° and 1.5°) and the
//!   best of them made, until `stones` pieces or
//!   no cut adds value. The final pieces' stones are then searched with the config's full
//!   search. Candidates run in parallel and are gathered in order, so the layout is the same
//!   on any number of threads; directions in the principal frame make a turned and moved
//!   rough give the layout turned and moved with it.
//!
//! Under a value objective the greedy search's jumps (a price per carat that jumps at a
//! weight) can lead it to a layout worth less than the heaviest one, so the weight layout's
//! saw plan is planned as well, its pieces' stones taken by value, and the better of the two
//! layouts kept ([`LayoutPlanner::plan`]).
//!
//! Under the colour objective (`kind = "colour"`, a coloured rough) the layout is planned by
//! value (or weight) and then each final piece's stone chosen by value × colour from its
//! candidates (`src/plan/layout/by_colour.rs`).
//!
//! With a laser ([`Cutter::Laser`]) the sawn layout is then improved pair by pair, each pair
//! of stones parted by a kerf-wide gap along a plane cut only between them
//! (`src/plan/layout/laser.rs`). What it is not: a global optimum: the saw plan is
//! greedy, cut by cut, the laser's a coordinate ascent (measured against brute force in
//! docs/plan.md).

use super::config::{Cutter, Objective, PlanConfig};
use super::rough::Rough;
use super::search::{principal_frame, Plan, Planner};
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane, Plane, Polyhedron};
use crate::optics::Material;
use glam::DQuat;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// The proxy of a stone when choosing the face that keeps an inclusion out: the 12 vertices
/// of a regular icosahedron (a ball-like solid, so the choice does not depend on a turn).
const PROXY: [[f64; 3]; 12] = {
    const P: f64 = 1.618_033_988_749_895;
    [
        [0.0, 1.0, P],
        [0.0, -1.0, P],
        [0.0, 1.0, -P],
        [0.0, -1.0, -P],
        [1.0, P, 0.0],
        [-1.0, P, 0.0],
        [1.0, -P, 0.0],
        [-1.0, -P, 0.0],
        [P, 0.0, 1.0],
        [-P, 0.0, 1.0],
        [P, 0.0, -1.0],
        [-P, 0.0, -1.0],
    ]
};

/// Saw directions taken from the rough's largest faces, besides the 13 of [`directions`].
const FACE_DIRECTIONS: usize = 6;

/// Saw candidates refined per cut (the best of different pieces or directions).
const REFINED: usize = 4;

/// One saw cut: the plane `normal·x = offset` (mm, the rough's coordinates); the kerf's slab
/// around it is lost.
#[derive(Clone, Debug, PartialEq)]
pub struct SawCut {
    /// The piece it cuts (`rough`, then `A`, `B`, `Aa`, …: the side `normal·x < offset` gets
    /// `a`/`A`).
    pub piece: String,
    /// Unit normal.
    pub normal: DVec3,
    /// Offset (mm).
    pub offset: f64,
    /// The volume the kerf takes from the piece (mm³).
    pub kerf_loss_mm3: f64,
    /// The piece it cuts (mm).
    pub piece_solid: Polyhedron,
}

/// One stone of a layout: its piece, its plan, the half-spaces that keep inclusions out and
/// the inclusions it holds.
#[derive(Clone, Debug)]
pub struct Stone {
    /// The family of its cut.
    pub family: String,
    /// The piece it is cut from (see [`SawCut::piece`]).
    pub piece: String,
    /// The piece as sawn (mm).
    pub piece_solid: Polyhedron,
    /// The stone, placed (its `yield_fraction` against the whole rough; its `objective`
    /// the value with the `included` factor when it holds an inclusion).
    pub plan: Plan,
    /// The half-spaces `normal·x <= offset` that keep inclusions out, with the inclusion's
    /// index.
    pub separations: Vec<(usize, Plane)>,
    /// The inclusions (indices) the stone holds, at the price table's `included` factor.
    pub holds: Vec<usize>,
    /// A layout ranked by colour: the stone's worth and colour factor (`plan.objective` is
    /// their product, `plan.colour` its face-up colour).
    pub colour: Option<ColourWorth>,
}

/// A stone's worth under `kind = "colour"` (`src/plan/layout/by_colour.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColourWorth {
    /// Its price-table value (a table given), else its carats.
    pub worth: f64,
    /// Its face-up chroma over the material's reference ([`super::colour::colour_factor`]).
    pub factor: f64,
}

/// A layout: the stones, the saw cuts in cutting order and what they lose.
#[derive(Clone, Debug)]
pub struct Layout {
    /// The stones, in the order of their pieces.
    pub stones: Vec<Stone>,
    /// The saw cuts, in cutting order.
    pub saw: Vec<SawCut>,
    /// The total objective (value, or carats).
    pub total: f64,
    /// The stones' carats.
    pub carats: f64,
    /// The stones' volume over the rough's.
    pub yield_fraction: f64,
    /// The volume the kerf takes (mm³).
    pub kerf_loss_mm3: f64,
    /// How the stones were parted: with a laser, `saw` holds the laser's cuts.
    pub cutter: Cutter,
    /// Every pair of stones and a plane between them with the kerf and both allowances.
    pub pairs: Vec<Parting>,
    /// Ranked by colour: the material's reference chroma of the colour factors.
    pub colour_reference: Option<f64>,
}

/// A piece of the rough: its label, half-spaces and solid.
#[derive(Clone, Debug)]
struct Piece {
    label: String,
    solid: Polyhedron,
}

/// How hard a piece's stone is searched.
#[derive(Clone, Copy, PartialEq)]
enum Effort {
    Screen,
    Full,
}

/// A stone found in a room: its family, plan, the planes keeping it off inclusions
/// (inclusion, plane) and the inclusions it holds.
type InRoom = (String, Plan, Vec<(usize, Plane)>, Vec<usize>);

/// Plans layouts of several stones in one rough.
pub struct LayoutPlanner<'a> {
    rough: &'a Rough,
    config: &'a PlanConfig,
    density: f64,
    inclusions: &'a [Inclusion],
    frame: DQuat,
    stop: Option<&'a AtomicBool>,
    material: Option<&'a Material>,
}

impl<'a> LayoutPlanner<'a> {
    /// A layout planner for `rough` under `config` (its `stones`, `kerf_mm`, `allowance_mm`,
    /// objective, families and search), `density` in g/cm³, keeping out `inclusions`.
    pub fn new(
        rough: &'a Rough,
        config: &'a PlanConfig,
        density: f64,
        inclusions: &'a [Inclusion],
    ) -> LayoutPlanner<'a> {
        LayoutPlanner {
            rough,
            config,
            density,
            inclusions,
            frame: principal_frame(rough.solid.vertices()),
            stop: None,
            material: None,
        }
    }

    /// The planner with the `material` whose face-up colour ranks a `kind = "colour"` layout.
    pub fn with_material(mut self, material: &'a Material) -> Self {
        self.material = Some(material);
        self
    }

    /// The planner, stopped when `stop` is raised.
    pub fn with_stop(mut self, stop: &'a AtomicBool) -> Self {
        self.stop = Some(stop);
        self
    }

    fn stopped(&self) -> bool {
        self.stop.is_some_and(|s| s.load(Ordering::SeqCst))
    }

    /// Each family's best `top` plans in `region` (a rough of the stone's room) at `effort`,
    /// in the config's order of the families.
    fn plans_in(&self, region: Polyhedron, effort: Effort, top: usize) -> Vec<(String, Plan)> {
        let mut cfg = self.config.clone();
        cfg.top = top;
        if effort == Effort::Screen {
            cfg.starts = cfg.starts.min(2);
            cfg.max_iterations = cfg.max_iterations.min(80);
        }
        let room = Rough {
            name: "piece".into(),
            solid: region,
            mesh_volume: None,
            ball: None,
            left_out: 0.0,
            hull_vertices: 0,
        };
        let mut planner = Planner::new(&room, &cfg, self.density);
        if effort == Effort::Screen {
            planner = planner.screening();
        }
        if let Some(s) = self.stop {
            planner = planner.with_stop(s);
        }
        let mut out = Vec::new();
        for f in &cfg.families {
            let Ok(plans) = planner.plan_family(f, &|| {}) else {
                continue;
            };
            let fits = plans.into_iter().filter(|p| p.scale >= cfg.min_width_mm);
            out.extend(fits.map(|p| (f.clone(), p)));
        }
        out
    }

    /// The region of a stone in `piece` kept off the inclusions it still meets: the piece
    /// moved in by the allowance, and per inclusion one face of its grown hull's far side.
    /// `None`: nothing is left.
    fn kept_out(&self, region: Polyhedron) -> Option<(Polyhedron, Vec<(usize, Plane)>)> {
        let mut region = region;
        let mut seps = Vec::new();
        let proxy: Vec<DVec3> = PROXY.iter().map(|p| DVec3::from_array(*p)).collect();
        for (i, inc) in self.inclusions.iter().enumerate() {
            if apart(&region, &inc.grown) {
                continue;
            }
            // The stone's side of a face: n·x >= d, as the half-space −n·x <= −d.
            let sides: Vec<Plane> = inc
                .grown
                .facets()
                .iter()
                .map(|f| Plane {
                    normal: -f.plane.normal,
                    offset: -f.plane.offset,
                })
                .collect();
            let best = widest(&region, &sides, &proxy);
            let (_, h) = best?;
            region = region
                .cut_by(&FacetPlane {
                    plane: h,
                    name: format!("keep-off-{}", i + 1),
                    tier: "inclusion".into(),
                })
                .ok()?;
            seps.push((i, h));
        }
        Some((region, seps))
    }

    /// The best stone of `piece` at `effort`, or `None` when none fits: the first of the
    /// most valuable of [`LayoutPlanner::candidates`].
    fn stone(&self, piece: &Piece, effort: Effort) -> Option<Stone> {
        let room = self.room(&piece.solid)?;
        let (family, plan, separations, holds) = self.stone_in(room, effort)?;
        Some(self.stone_of(piece, family, plan, separations, holds))
    }

    /// The stones of `piece` at `effort` ([`LayoutPlanner::candidates_in`] its room).
    fn candidates(&self, piece: &Piece, effort: Effort, top: usize) -> Vec<Stone> {
        let Some(room) = self.room(&piece.solid) else {
            return Vec::new();
        };
        self.candidates_in(room, effort, top)
            .into_iter()
            .map(|(family, plan, seps, holds)| self.stone_of(piece, family, plan, seps, holds))
            .collect()
    }

    /// The room of a stone in a piece `solid`: the piece moved in by the allowance (`None`
    /// when nothing is left).
    fn room(&self, solid: &Polyhedron) -> Option<Polyhedron> {
        Polyhedron::from_planes_pruned(&moved_in(solid, self.config.allowance_mm)).ok()
    }

    /// The best stone in `room` (a piece moved in by the allowance) at `effort`: the first of
    /// the most valuable of [`LayoutPlanner::candidates_in`].
    fn stone_in(&self, room: Polyhedron, effort: Effort) -> Option<InRoom> {
        let mut best: Option<InRoom> = None;
        for s in self.candidates_in(room, effort, 1) {
            if best.as_ref().is_none_or(|b| s.1.objective > b.1.objective) {
                best = Some(s);
            }
        }
        best
    }

    /// The stones in `room` at `effort`: each family's best `top` kept off the inclusions,
    /// then (a price table with an `included` factor, an inclusion in the room) each
    /// family's best `top` that may hold them, at that factor when one does.
    fn candidates_in(&self, room: Polyhedron, effort: Effort, top: usize) -> Vec<InRoom> {
        if self.stopped() {
            return Vec::new();
        }
        let meets: Vec<usize> = self
            .inclusions
            .iter()
            .enumerate()
            .filter(|(_, inc)| !apart(&room, &inc.grown))
            .map(|(i, _)| i)
            .collect();
        let mut out = Vec::new();
        if let Some((region, separations)) = self.kept_out(room.clone()) {
            for (family, plan) in self.plans_in(region, effort, top) {
                out.push((family, plan, separations.clone(), Vec::new()));
            }
        }
        let factor = match &self.config.objective {
            Objective::Value(t) => t.included,
            _ => None,
        };
        if let (Some(f), false) = (factor, meets.is_empty()) {
            for (family, mut plan) in self.plans_in(room, effort, top) {
                // The stone may not hold an inclusion, only the margin around it.
                let solid = plan.placed_solid().ok();
                let holds: Vec<usize> = meets
                    .iter()
                    .copied()
                    .filter(|&i| {
                        solid
                            .as_ref()
                            .is_none_or(|s| !apart(s, &self.inclusions[i].grown))
                    })
                    .collect();
                if !holds.is_empty() {
                    plan.objective *= f;
                }
                out.push((family, plan, Vec::new(), holds));
            }
        }
        out
    }

    fn stone_of(
        &self,
        piece: &Piece,
        family: String,
        mut plan: Plan,
        separations: Vec<(usize, Plane)>,
        holds: Vec<usize>,
    ) -> Stone {
        plan.yield_fraction = plan.volume_mm3 / self.rough.volume();
        Stone {
            family,
            piece: piece.label.clone(),
            piece_solid: piece.solid.clone(),
            plan,
            separations,
            holds,
            colour: None,
        }
    }

    /// `piece` sawn along `u·x = c`: the two pieces (`None` when either is empty) and the
    /// kerf's loss.
    fn saw(&self, piece: &Piece, u: DVec3, c: f64) -> Option<(Piece, Piece, f64)> {
        let k = 0.5 * self.config.kerf_mm;
        let name = format!("saw-{}", piece.label);
        let a = piece
            .solid
            .cut_by(&FacetPlane::new(u, c - k, name.clone(), "saw"))
            .ok()?;
        let b = piece
            .solid
            .cut_by(&FacetPlane::new(-u, -(c + k), name, "saw"))
            .ok()?;
        let loss = (piece.solid.volume() - a.volume() - b.volume()).max(0.0);
        let (la, lb) = if piece.label == "rough" {
            ("A".to_string(), "B".to_string())
        } else {
            (format!("{}a", piece.label), format!("{}b", piece.label))
        };
        Some((
            Piece {
                label: la,
                solid: a,
            },
            Piece {
                label: lb,
                solid: b,
            },
            loss,
        ))
    }

    /// The value of a piece whose stone's room is `room` sawn along `u·x = c`, at screening
    /// effort (0 for a side where no stone fits). Each side's room is `room` cut by the saw's
    /// plane moved in by half the kerf and the allowance: the piece sawn and then moved in by
    /// the allowance, exactly (the inner parallel body of an intersection of half-spaces is
    /// the intersection of each moved in), by one clip instead of two solids rebuilt.
    fn split_value(&self, room: &Polyhedron, u: DVec3, c: f64) -> f64 {
        let k = 0.5 * self.config.kerf_mm + self.config.allowance_mm;
        [(u, c - k), (-u, -(c + k))]
            .into_iter()
            .filter_map(|(n, d)| room.cut_by(&FacetPlane::new(n, d, "saw", "saw")).ok())
            .filter_map(|side| self.stone_in(side, Effort::Screen))
            .map(|s| s.1.objective)
            .sum()
    }

    /// Plan the layout: at most `config.stones` stones (see the module documentation). `tick`
    /// runs after each saw candidate is judged. Under a value objective the weight layout's
    /// saw plan is planned too and its pieces' stones taken by value (each the better of the
    /// value search's stone and the weight search's priced), and the better layout kept: the
    /// layout ranked by value is never worth less than the weight layout priced by the same
    /// table.
    /// Under `kind = "colour"`, see `src/plan/layout/by_colour.rs`.
    pub fn plan(&self, tick: &(dyn Fn() + Sync)) -> Result<Layout> {
        if let Objective::Colour(prices) = &self.config.objective {
            return self.coloured(prices.as_ref(), tick);
        }
        let sawn = self.sawn(tick)?;
        match self.config.cutter {
            Cutter::Saw => Ok(sawn),
            Cutter::Laser => self.laser(sawn),
        }
    }

    /// The layout sawn (see [`LayoutPlanner::plan`]).
    fn sawn(&self, tick: &(dyn Fn() + Sync)) -> Result<Layout> {
        let valued = self.greedy(tick)?;
        let Objective::Value(table) = &self.config.objective else {
            return Ok(valued);
        };
        let mut cfg = self.config.clone();
        cfg.objective = Objective::Weight;
        let by_weight = LayoutPlanner {
            config: &cfg,
            ..*self
        };
        let heavy = by_weight.greedy(tick)?;
        let stones: Vec<Stone> = heavy
            .stones
            .par_iter()
            .map(|w| {
                let mut priced = w.clone();
                priced.plan.objective = table.value(w.plan.carats, w.plan.grade);
                let piece = Piece {
                    label: w.piece.clone(),
                    solid: w.piece_solid.clone(),
                };
                match self.stone(&piece, Effort::Full) {
                    Some(v) if v.plan.objective > priced.plan.objective => v,
                    _ => priced,
                }
            })
            .collect();
        if self.stopped() {
            return Err(Error::invalid("plan", "interrupted"));
        }
        let seeded = self.layout_of(stones, heavy.saw)?;
        // Ties keep the value search's own layout.
        Ok(if seeded.total > valued.total {
            seeded
        } else {
            valued
        })
    }

    /// The greedy saw plan and its pieces' stones (see the module documentation).
    fn greedy(&self, tick: &(dyn Fn() + Sync)) -> Result<Layout> {
        let whole = Piece {
            label: "rough".into(),
            solid: self.rough.solid.clone(),
        };
        let mut pieces: Vec<(Piece, f64)> = Vec::new();
        let v0 = self
            .stone(&whole, Effort::Screen)
            .map_or(0.0, |s| s.plan.objective);
        pieces.push((whole, v0));
        let mut saw: Vec<SawCut> = Vec::new();
        let dirs = self.saw_directions();
        let m = self.config.saw_offsets;
        while pieces.len() < self.config.stones && !self.stopped() {
            // Every piece × direction × offset, judged in parallel, gathered in order.
            let rooms: Vec<Option<Polyhedron>> = pieces
                .par_iter()
                .map(|(p, _)| self.room(&p.solid))
                .collect();
            let mut cands: Vec<(usize, DVec3, f64, f64)> = Vec::new();
            for (i, (p, _)) in pieces.iter().enumerate() {
                for u in &dirs {
                    let (lo, hi) = extent(&p.solid, *u);
                    for j in 0..m {
                        let c = lo + (hi - lo) * (j + 1) as f64 / (m + 1) as f64;
                        cands.push((i, *u, c, (hi - lo) / (m + 1) as f64));
                    }
                }
            }
            let gains: Vec<f64> = cands
                .par_iter()
                .map(|&(i, u, c, _)| {
                    let g =
                        rooms[i].as_ref().map_or(0.0, |r| self.split_value(r, u, c)) - pieces[i].1;
                    tick();
                    g
                })
                .collect();
            // The best few candidates (at most one per piece and direction) refined, the
            // best refined one made.
            let mut order: Vec<usize> =
                (0..cands.len()).filter(|&k| gains[k].is_finite()).collect();
            order.sort_by(|&x, &y| gains[y].total_cmp(&gains[x]).then(x.cmp(&y)));
            let mut picked: Vec<usize> = Vec::new();
            for k in order {
                if picked.len() >= REFINED {
                    break;
                }
                let (i, u, ..) = cands[k];
                if !picked.iter().any(|&q| cands[q].0 == i && cands[q].1 == u) {
                    picked.push(k);
                }
            }
            let refined: Vec<(usize, DVec3, f64, f64)> = picked
                .par_iter()
                .map(|&k| {
                    let (i, u, c, step) = cands[k];
                    let Some(room) = rooms[i].as_ref() else {
                        return (i, u, c, f64::NEG_INFINITY);
                    };
                    let centre = pieces[i].0.solid.centroid();
                    let (u, c, v) = self.refine(room, centre, u, c, step, gains[k] + pieces[i].1);
                    (i, u, c, v - pieces[i].1)
                })
                .collect();
            let Some(&(i, u, c, g)) = refined
                .iter()
                .enumerate()
                .max_by(|a, b| a.1 .3.total_cmp(&b.1 .3).then(b.0.cmp(&a.0)))
                .map(|(_, r)| r)
            else {
                break;
            };
            if g.is_nan() || g <= 1e-9 * pieces.iter().map(|p| p.1).sum::<f64>().max(1e-300) {
                break;
            }
            let Some((a, b, loss)) = self.saw(&pieces[i].0, u, c) else {
                break;
            };
            saw.push(SawCut {
                piece: pieces[i].0.label.clone(),
                normal: u,
                offset: c,
                kerf_loss_mm3: loss,
                piece_solid: pieces[i].0.solid.clone(),
            });
            let va = self
                .stone(&a, Effort::Screen)
                .map_or(0.0, |s| s.plan.objective);
            let vb = self
                .stone(&b, Effort::Screen)
                .map_or(0.0, |s| s.plan.objective);
            pieces.splice(i..=i, [(a, va), (b, vb)]);
        }
        if self.stopped() {
            return Err(Error::invalid("plan", "interrupted"));
        }
        // The final pieces' stones, with the full search.
        let stones: Vec<Option<Stone>> = pieces
            .par_iter()
            .map(|(p, _)| self.stone(p, Effort::Full))
            .collect();
        self.layout_of(stones.into_iter().flatten().collect(), saw)
    }

    /// The layout of `stones` sawn by `saw`, with its totals; an error when it holds none.
    fn layout_of(&self, stones: Vec<Stone>, saw: Vec<SawCut>) -> Result<Layout> {
        if stones.is_empty() {
            return Err(Error::invalid(
                "ROUGH",
                format!(
                    "no stone of the families asked fits in the rough {} with the allowance {} mm and the inclusions' margin",
                    self.rough.name, self.config.allowance_mm
                ),
            ));
        }
        let total = stones.iter().map(|s| s.plan.objective).sum();
        let carats = stones.iter().map(|s| s.plan.carats).sum();
        let volume: f64 = stones.iter().map(|s| s.plan.volume_mm3).sum();
        let pairs = laser::sawn_pairs(&stones, &saw);
        Ok(Layout {
            total,
            carats,
            yield_fraction: volume / self.rough.volume(),
            kerf_loss_mm3: saw.iter().map(|s| s.kerf_loss_mm3).sum(),
            cutter: Cutter::Saw,
            pairs,
            stones,
            saw,
            colour_reference: None,
        })
    }
}

/// Plan a layout of `config.stones` stones in `rough` keeping off `inclusions`, for
/// `material`'s density (and, under `kind = "colour"`, its colour; a colourless material
/// refuses it): `tick` after each saw candidate, a raised `stop` ends it (an error).
pub fn plan_layout(
    rough: &Rough,
    config: &PlanConfig,
    material: &crate::optics::Material,
    inclusions: &[Inclusion],
    tick: &(dyn Fn() + Sync),
    stop: Option<&AtomicBool>,
) -> Result<Layout> {
    super::colour::check(config, material)?;
    if rough.ball.is_some() {
        return Err(Error::invalid(
            "ROUGH",
            "the sphere is an exact ball for single plans; a layout of several stones or with inclusions needs a polyhedral rough",
        ));
    }
    let mut planner =
        LayoutPlanner::new(rough, config, material.density, inclusions).with_material(material);
    if let Some(s) = stop {
        planner = planner.with_stop(s);
    }
    planner.plan(tick)
}

/// About how many saw candidates [`LayoutPlanner::plan`] judges at most (for a progress bar).
pub fn candidates(config: &PlanConfig) -> u64 {
    let per_piece = ((13 + 4 * FACE_DIRECTIONS) * config.saw_offsets) as u64;
    let greedy: u64 = (1..config.stones as u64).map(|k| k * per_piece).sum();
    // A value objective plans the weight layout's saw plan too.
    match config.objective {
        Objective::Value(_) | Objective::Colour(Some(_)) => 2 * greedy,
        _ => greedy,
    }
}

mod by_colour;
mod inclusion;
mod laser;
mod saw;
mod solids;

pub use solids::directions;
use solids::{apart, extent, moved_in, widest};

pub use inclusion::Inclusion;
pub use laser::Parting;

#[cfg(test)]
mod tests;
