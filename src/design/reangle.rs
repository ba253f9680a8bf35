//! Re-angling tiers with the design's meets kept: new angles give new facet normals (each
//! facet keeps its azimuth and its side), [`super::meets::solve_depths`] gives the depths that
//! keep the meets, and the solid is rebuilt and checked to be the same design — the same
//! facets, the same adjacency, every meet still a meet.

use super::meets::{find_meets, least_squares_point, solve_depths, DepthProblem, Meet};
use super::Gear;
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{facet_angle_deg, DVec3, FacetPlane, Polyhedron};
use std::collections::BTreeSet;

/// A solid seen as tiers: which tier each facet is in, each tier's depth, and the meets to
/// keep. Girdle tiers (vertical facets) are held, and so is the height of every meet on the
/// girdle: together they fix the scale and the girdle's thickness.
#[derive(Clone, Debug)]
pub struct TierModel {
    /// The solid as designed.
    pub solid: Polyhedron,
    /// Each facet's tier.
    pub tier_of: Vec<usize>,
    /// Each tier's name.
    pub names: Vec<String>,
    /// Each tier's depth (the mean of its facets' offsets).
    pub depths: Vec<f64>,
    /// The meets, found at the model's tolerance.
    pub meets: Vec<Meet>,
    /// Tiers held at their depth.
    pub held: Vec<bool>,
    /// Meets held at their height.
    pub held_z: Vec<Option<f64>>,
    /// The tolerance the meets were found at: a meet further off than this is open.
    pub tol: f64,
    /// Each meet's own allowance on top of `tol`: a design whose rounded file cannot put a
    /// meet's planes exactly through one point keeps it as close as it was (0 by default).
    pub slack: Vec<f64>,
    /// The tolerance the meets were found at.
    found_at: f64,
}

/// The tolerance (of W) within which four or more facet planes through one point make a meet
/// by default: 1e-4 W (0.65 µm on a 6.5 mm stone), above the rounding of files that write
/// depths to five decimals and far below anything a cutter can see.
pub const MEET_TOL: f64 = 1e-4;

/// A facet is on the girdle when its normal is this close to horizontal.
const GIRDLE_Z: f64 = 1e-9;

impl TierModel {
    /// The model of a cut with its tiers as GemCad lines ([`super::tiers`], on the design's
    /// own gear): tier names are the lines' names, made unique by a `#2`, `#3` … suffix where
    /// two lines share one.
    ///
    /// A cut without a GemCad record (a preset, a TOML list of facets, a mesh) has its tiers as
    /// its symmetry makes them: facets of one tier name whose angles agree within
    /// [`SAME_ANGLE`] degrees and depths within [`SAME_DEPTH`] of W (a mesh's rounded
    /// coordinates leave its symmetric facets that far apart).
    pub fn of_cut(cut: &Cut, tol: f64) -> Result<Self> {
        let Some(record) = &cut.record else {
            return Self::of_solid(&cut.solid, tol);
        };
        let lines = super::tiers(cut, Gear::for_record(record, 0), 1.0);
        let mut tier_of = vec![usize::MAX; cut.solid.facets().len()];
        let mut names: Vec<String> = Vec::new();
        for (t, line) in lines.iter().enumerate() {
            let base = if line.name.is_empty() {
                format!("line-{}", t + 1)
            } else {
                line.name.clone()
            };
            names.push(unique(&names, &base));
            for f in &line.facets {
                if let Some(i) = cut.solid.facets().iter().position(|g| g.name == f.name) {
                    tier_of[i] = t;
                }
            }
        }
        TierModel::new(cut.solid.clone(), tier_of, names, tol)
    }

    /// The model of a solid whose facets are grouped into tiers by tier name, angle and depth
    /// (see [`TierModel::of_cut`]).
    pub fn of_solid(solid: &Polyhedron, tol: f64) -> Result<Self> {
        // (name, angle, depth, side) of each tier so far.
        let mut tiers: Vec<(String, f64, f64, i8)> = Vec::new();
        let mut tier_of = Vec::new();
        for f in solid.facets() {
            let n = f.plane.normal;
            let side = if n.z > GIRDLE_Z {
                1
            } else if n.z < -GIRDLE_Z {
                -1
            } else {
                0
            };
            let angle = facet_angle_deg(n);
            let name = super::token(&f.tier);
            let found = tiers.iter().position(|(tn, a, d, s)| {
                *tn == name
                    && *s == side
                    && (a - angle).abs() <= SAME_ANGLE
                    && (d - f.plane.offset).abs() <= SAME_DEPTH
            });
            tier_of.push(found.unwrap_or_else(|| {
                tiers.push((name, angle, f.plane.offset, side));
                tiers.len() - 1
            }));
        }
        let mut names: Vec<String> = Vec::new();
        for (t, (name, ..)) in tiers.iter().enumerate() {
            let base = if name.is_empty() {
                format!("tier-{}", t + 1)
            } else {
                name.clone()
            };
            names.push(unique(&names, &base));
        }
        TierModel::new(solid.clone(), tier_of, names, tol)
    }

    /// The tolerance the meets were found at (of W): `tol` unless the model was told to keep
    /// meets more tightly than it found them ([`super::DesignSpace`] does).
    pub fn meet_tol(&self) -> f64 {
        self.found_at
    }

    /// The names of the tiers a meet joins, each once, in the order of its facets.
    pub fn meet_tiers(&self, meet: &Meet) -> Vec<&str> {
        let mut out: Vec<&str> = Vec::new();
        for &f in &meet.facets {
            let name = self.names[self.tier_of[f]].as_str();
            if !out.contains(&name) {
                out.push(name);
            }
        }
        out
    }

    /// The model of `solid` with tiers given by `tier_of` (facet → tier, with `names`), meets
    /// at tolerance `tol` (of W).
    pub fn new(
        solid: Polyhedron,
        tier_of: Vec<usize>,
        names: Vec<String>,
        tol: f64,
    ) -> Result<Self> {
        let nt = names.len();
        if tier_of.len() != solid.facets().len() || tier_of.iter().any(|&t| t >= nt) {
            return Err(Error::Geometry("tier model: a facet without a tier".into()));
        }
        let mut sums = vec![(0.0, 0usize); nt];
        for (f, &t) in solid.facets().iter().zip(&tier_of) {
            sums[t].0 += f.plane.offset;
            sums[t].1 += 1;
        }
        let depths: Vec<f64> = sums.iter().map(|(s, n)| s / (*n).max(1) as f64).collect();
        let girdle = |f: usize| solid.facets()[f].plane.normal.z.abs() <= GIRDLE_Z;
        let mut held = vec![false; nt];
        for (f, &t) in tier_of.iter().enumerate() {
            if girdle(f) {
                held[t] = true;
            }
        }
        if !held.iter().any(|&h| h) {
            // No girdle: the deepest tier fixes the scale.
            let t = (0..nt)
                .max_by(|&a, &b| depths[a].total_cmp(&depths[b]))
                .unwrap_or(0);
            if nt > 0 {
                held[t] = true;
            }
        }
        let meets = find_meets(&solid, tol);
        let held_z = meets
            .iter()
            .map(|m| m.facets.iter().any(|&f| girdle(f)).then_some(m.point.z))
            .collect();
        let slack = vec![0.0; meets.len()];
        Ok(TierModel {
            found_at: tol,
            slack,
            solid,
            tier_of,
            names,
            depths,
            meets,
            held,
            held_z,
            tol,
        })
    }

    /// Each tier's angle to the girdle plane in degrees (the mean over its facets).
    pub fn angles(&self) -> Vec<f64> {
        let mut sums = vec![(0.0, 0usize); self.names.len()];
        for (f, &t) in self.solid.facets().iter().zip(&self.tier_of) {
            sums[t].0 += facet_angle_deg(f.plane.normal);
            sums[t].1 += 1;
        }
        sums.iter().map(|(s, n)| s / (*n).max(1) as f64).collect()
    }

    /// The facet planes with the tiers in `angles` (tier → new angle to the girdle plane, in
    /// degrees, 0–90) turned to them, at the depths that keep the meets; with how far each meet
    /// is from kept.
    pub fn reangled(&self, angles: &[Option<f64>]) -> Result<Reangled> {
        let normals: Vec<DVec3> = self
            .solid
            .facets()
            .iter()
            .zip(&self.tier_of)
            .map(|(f, &t)| match angles.get(t).copied().flatten() {
                Some(a) => turned(f.plane.normal, a),
                None => f.plane.normal,
            })
            .collect();
        // Keep every meet the angles allow: solve, and while some meet is off by more than
        // the tolerance, give up the worst one (least squares spreads an impossible meet's
        // error over its neighbours) and solve again.
        let mut open = vec![false; self.meets.len()];
        let (solve, kept) = loop {
            let kept: Vec<usize> = (0..self.meets.len()).filter(|&m| !open[m]).collect();
            let meets: Vec<Vec<usize>> =
                kept.iter().map(|&m| self.meets[m].facets.clone()).collect();
            let held_z: Vec<Option<f64>> = kept.iter().map(|&m| self.held_z[m]).collect();
            let solve = solve_depths(&DepthProblem {
                normals: &normals,
                tier_of: &self.tier_of,
                depths: &self.depths,
                held: &self.held,
                meets: &meets,
                held_z: &held_z,
            })?;
            let worst = (0..kept.len()).max_by(|&a, &b| solve.gaps[a].total_cmp(&solve.gaps[b]));
            match worst {
                Some(k) if solve.gaps[k] > self.tol + self.slack[kept[k]] => open[kept[k]] = true,
                _ => break (solve, kept),
            }
        };
        // An opened meet's gap: how far its planes are from sharing a point at the new depths.
        let mut gaps: Vec<f64> = self
            .meets
            .iter()
            .map(|m| spread(&normals, &self.tier_of, &solve.depths, &m.facets))
            .collect();
        for (k, &m) in kept.iter().enumerate() {
            gaps[m] = solve.gaps[k];
        }
        let planes = self
            .solid
            .facets()
            .iter()
            .zip(&normals)
            .zip(&self.tier_of)
            .map(|((f, &n), &t)| {
                FacetPlane::new(n, solve.depths[t], f.name.clone(), f.tier.clone())
            })
            .collect();
        Ok(Reangled { planes, gaps })
    }
}

/// Facets of one tier name within this many degrees of one angle are one tier (of a cut
/// without a GemCad record).
pub const SAME_ANGLE: f64 = 1e-3;

/// … and within this distance (of W) of one depth.
pub const SAME_DEPTH: f64 = 1e-5;

/// `base`, or `base#2`, `base#3` … when `names` has it.
fn unique(names: &[String], base: &str) -> String {
    let mut name = base.to_string();
    let mut k = 1;
    while names.contains(&name) {
        k += 1;
        name = format!("{base}#{k}");
    }
    name
}

/// How far the planes of `facets` are from passing through one point: the largest distance
/// of a plane from their least-squares point (infinite when they do not fix a point).
fn spread(normals: &[DVec3], tier_of: &[usize], depths: &[f64], facets: &[usize]) -> f64 {
    let planes: Vec<(DVec3, f64)> = facets
        .iter()
        .map(|&f| (normals[f], depths[tier_of[f]]))
        .collect();
    match least_squares_point(&planes) {
        Some(p) => planes
            .iter()
            .map(|(n, d)| (n.dot(p) - d).abs())
            .fold(0.0, f64::max),
        None => f64::INFINITY,
    }
}

/// `n` turned to `angle` degrees from the girdle plane about the vertical plane through it:
/// the same azimuth and side. A flat facet (table, culet) has no azimuth and stays flat.
pub fn turned(n: DVec3, angle: f64) -> DVec3 {
    let h = n.x.hypot(n.y);
    if h <= 1e-12 {
        return n;
    }
    let a = angle.to_radians();
    let z = if n.z >= 0.0 { a.cos() } else { -a.cos() };
    DVec3::new(a.sin() * n.x / h, a.sin() * n.y / h, z)
}

/// The planes of a re-angled design and each meet's gap.
#[derive(Clone, Debug)]
pub struct Reangled {
    /// The facet planes, in the model's facet order.
    pub planes: Vec<FacetPlane>,
    /// Each meet's gap (0 where it is kept).
    pub gaps: Vec<f64>,
}

/// The facet adjacency of a solid: the unordered pairs of facet names that share an edge.
pub fn adjacency(s: &Polyhedron) -> BTreeSet<(String, String)> {
    adjacency_over(s, 0.0)
}

/// The pairs of facet names that share an edge longer than `min` (of W). At a meet, where
/// four or more facets pass through one point, which of them share an edge is a matter of
/// rounding (an edge of 1e-9 W appears between two of them, or between the other two): a
/// design's own adjacency is the edges longer than its meet tolerance.
pub fn adjacency_over(s: &Polyhedron, min: f64) -> BTreeSet<(String, String)> {
    let v = s.vertices();
    s.edges()
        .iter()
        .filter(|e| v[e.a].distance(v[e.b]) > min)
        .map(|e| {
            let (a, b) = (&s.facets()[e.facets[0]].name, &s.facets()[e.facets[1]].name);
            if a <= b {
                (a.clone(), b.clone())
            } else {
                (b.clone(), a.clone())
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::tests::{brute_vertices, same_vertices};
    use std::collections::BTreeMap;

    /// Tiers as GemCad lines: facets of one tier name with the same angle and depth.
    fn model(s: &Polyhedron) -> TierModel {
        let mut names: Vec<String> = Vec::new();
        let tier_of = s
            .facets()
            .iter()
            .map(|f| {
                let z = f.plane.normal.z;
                let side = if z > GIRDLE_Z {
                    "+"
                } else if z < -GIRDLE_Z {
                    "-"
                } else {
                    "0"
                };
                let key = format!(
                    "{}{side}@{:.6}/{:.8}",
                    f.tier,
                    facet_angle_deg(f.plane.normal),
                    f.plane.offset
                );
                names.iter().position(|n| *n == key).unwrap_or_else(|| {
                    names.push(key);
                    names.len() - 1
                })
            })
            .collect();
        TierModel::new(s.clone(), tier_of, names, 1e-9).unwrap()
    }

    #[test]
    fn a_design_read_from_asc_has_its_lines_as_tiers_and_replays_to_itself() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let text = crate::io::asc::write(&cut, 96);
        let back = crate::io::asc::parse(text.as_bytes(), "t.asc")
            .unwrap()
            .to_cut("t")
            .unwrap();
        let m = TierModel::of_cut(&back, 1e-6).unwrap();
        // One tier per GemCad line; the 16 girdle facets and the table each one line.
        let lines = text.lines().filter(|l| l.starts_with("a ")).count();
        assert_eq!(m.names.len(), lines, "{:?}", m.names);
        assert!(m.tier_of.iter().all(|&t| t < lines));
        let r = m.reangled(&vec![None; lines]).unwrap();
        // The file's 8-decimal depths leave meets open by ~1e-8: the first solve snaps them
        // (the design adopts its meets), moving no vertex further than 1e-6 of W …
        assert!(r.gaps.iter().all(|g| *g < 1e-6), "{:?}", r.gaps);
        let snapped = Polyhedron::from_planes(&r.planes).unwrap();
        for p in back.solid.vertices() {
            let d = snapped
                .vertices()
                .iter()
                .map(|q| q.distance(*p))
                .fold(f64::MAX, f64::min);
            assert!(d < 1e-6, "vertex {p} moved {d}");
        }
        // … and the snapped design replays to itself within 1e-9, every vertex and facet.
        let m2 = TierModel::new(snapped.clone(), m.tier_of.clone(), m.names.clone(), 1e-6).unwrap();
        assert_eq!(m2.meets.len(), m.meets.len());
        let again =
            Polyhedron::from_planes(&m2.reangled(&vec![None; lines]).unwrap().planes).unwrap();
        same_vertices(&snapped, &again, 1e-9);
        assert_eq!(adjacency(&snapped), adjacency(&again));
        for (a, b) in snapped.facets().iter().zip(again.facets()) {
            assert!(
                (a.plane.offset - b.plane.offset).abs() < 1e-9
                    && a.plane.normal.distance(b.plane.normal) < 1e-12
            );
        }
    }

    #[test]
    fn replaying_a_design_at_its_own_angles_gives_the_same_solid() {
        for name in ["tolkowsky", "princess", "emerald", "oval", "old-european"] {
            let cut = crate::io::load_cut(name).unwrap();
            let m = model(&cut.solid);
            let r = m.reangled(&vec![None; m.names.len()]).unwrap();
            assert!(r.gaps.iter().all(|g| *g < 1e-9), "{name}: {:?}", r.gaps);
            let s = Polyhedron::from_planes(&r.planes).unwrap();
            same_vertices(&cut.solid, &s, 1e-9);
            assert_eq!(adjacency(&cut.solid), adjacency(&s), "{name}");
        }
    }

    #[test]
    fn the_design_path_lands_on_the_family_with_the_same_pavilion() {
        // tolkowsky's pavilion mains and lower halves turned to the angles the family gives
        // them at pavilion_angle 41.25 (its lower halves keep their length, so they turn too):
        // the meets fix the depths, and the solid is the family's.
        let base = crate::io::load_cut("tolkowsky").unwrap();
        let family = base
            .with_params(&BTreeMap::from([("pavilion_angle".to_string(), 41.25)]))
            .unwrap();
        let m = model(&base.solid);
        let target = model(&family.solid).angles();
        let angles: Vec<Option<f64>> = m
            .names
            .iter()
            .zip(&target)
            .map(|(n, a)| n.split('@').next().unwrap().ends_with('-').then_some(*a))
            .collect();
        let r = m.reangled(&angles).unwrap();
        assert!(r.gaps.iter().all(|g| *g < 1e-9));
        let s = Polyhedron::from_planes(&r.planes).unwrap();
        same_vertices(&family.solid, &s, 1e-9);
        assert_eq!(adjacency(&family.solid), adjacency(&s));
    }

    #[test]
    fn a_kept_meet_is_still_a_meet_by_brute_force_and_an_opened_one_is_reported() {
        let base = crate::io::load_cut("tolkowsky").unwrap();
        let m = model(&base.solid);
        let angles = m.angles();
        // Mains and lower halves both turned (each by its own amount): every meet kept.
        let turn: Vec<Option<f64>> = m
            .names
            .iter()
            .zip(&angles)
            .map(|(n, a)| match n.as_str() {
                n if n.starts_with("pavilion-main-") => Some(a + 0.6),
                n if n.starts_with("lower-half-") => Some(a + 0.4),
                _ => None,
            })
            .collect();
        let r = m.reangled(&turn).unwrap();
        let brute = brute_vertices(&r.planes);
        let s = Polyhedron::from_planes(&r.planes).unwrap();
        assert_eq!(s.facets().len(), base.solid.facets().len());
        assert_eq!(adjacency(&base.solid), adjacency(&s));
        for (meet, gap) in m.meets.iter().zip(&r.gaps) {
            let names: BTreeSet<String> = meet
                .facets
                .iter()
                .map(|&f| base.solid.facets()[f].name.clone())
                .collect();
            let found = brute.iter().any(|(_, on)| names.is_subset(on));
            assert_eq!(*gap < 1e-9, found, "meet {names:?}: gap {gap}");
            assert!(found, "meet {names:?} opened by {gap}");
        }
    }

    /// A square "design": a girdle of four vertical facets, a flat base, and a pyramid crown
    /// of two tiers (A at azimuths 0° and 180°, B at 90° and 270°) at one angle, cut to the
    /// girdle's top corners and meeting at an apex.
    fn square_pyramid() -> (Polyhedron, Vec<usize>, Vec<String>) {
        let (half, top, angle) = (0.5f64, 0.05f64, 40f64.to_radians());
        let mut planes = Vec::new();
        let mut tier_of = Vec::new();
        for k in 0..4 {
            let phi = k as f64 * std::f64::consts::FRAC_PI_2;
            let (c, s) = (phi.cos(), phi.sin());
            planes.push(FacetPlane::new(
                DVec3::new(c, s, 0.0),
                half,
                format!("G{k}"),
                "girdle",
            ));
            tier_of.push(0);
            let n = DVec3::new(angle.sin() * c, angle.sin() * s, angle.cos());
            // Through the girdle's top edge on this side.
            let d = n.dot(DVec3::new(half * c, half * s, top));
            planes.push(FacetPlane::new(
                n,
                d,
                format!("{}{k}", ["A", "B"][k % 2]),
                "crown",
            ));
            tier_of.push(1 + k % 2);
        }
        planes.push(FacetPlane::new(DVec3::NEG_Z, 0.3, "base", "base"));
        tier_of.push(3);
        let names = ["G", "A", "B", "base"].map(String::from).to_vec();
        (Polyhedron::from_planes(&planes).unwrap(), tier_of, names)
    }

    #[test]
    fn a_meet_the_angles_cannot_keep_is_reported_open() {
        let (s, tier_of, names) = square_pyramid();
        // Facet order in the solid is the planes' order.
        let m = TierModel::new(s, tier_of, names, 1e-9).unwrap();
        let apex = m
            .meets
            .iter()
            .position(|mt| mt.facets.len() == 4 && mt.point.x.abs() < 1e-12);
        let apex = apex.expect("the apex is a meet");
        assert_eq!(m.meets.len(), 5, "four girdle corners and the apex");
        // A and B turned together: everything kept.
        let both = m.reangled(&[None, Some(42.0), Some(42.0), None]).unwrap();
        assert!(both.gaps.iter().all(|g| *g < 1e-12), "{:?}", both.gaps);
        // A alone: the corners are kept (A's depth follows them), the apex opens.
        let a = m.reangled(&[None, Some(42.0), None, None]).unwrap();
        for (k, g) in a.gaps.iter().enumerate() {
            assert_eq!(k == apex, *g > 1e-6, "meet {k}: gap {g}");
        }
    }
}
