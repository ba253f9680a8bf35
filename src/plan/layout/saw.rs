//! The saw cuts a layout tries: the directions and the refinement of the best cuts.

use super::solids::directions;
use super::{LayoutPlanner, FACE_DIRECTIONS};
use crate::geometry::{DVec3, Polyhedron};
use glam::DQuat;
use rayon::prelude::*;

impl LayoutPlanner<'_> {
    /// The saw directions: the normals of the rough's largest faces (a crystal is sawn along
    /// its faces), the directions to its farthest corners, then the principal frame's (a
    /// symmetric rough's principal frame is any frame: its own directions come first).
    pub(super) fn saw_directions(&self) -> Vec<DVec3> {
        let mut dirs: Vec<DVec3> = Vec::new();
        let mut faces: Vec<(f64, DVec3)> = (0..self.rough.solid.facets().len())
            .map(|i| {
                let poly = self.rough.solid.facet_polygon(i);
                let area = (1..poly.len().saturating_sub(1))
                    .map(|k| 0.5 * (poly[k] - poly[0]).cross(poly[k + 1] - poly[0]).length())
                    .sum::<f64>();
                (area, self.rough.solid.facets()[i].plane.normal)
            })
            .collect();
        faces.sort_by(|a, b| b.0.total_cmp(&a.0));
        // Faces as large as the last one kept are all kept (a symmetric rough's equal faces
        // are taken together, whatever their order).
        let least = faces
            .get(FACE_DIRECTIONS.saturating_sub(1))
            .map_or(0.0, |f| f.0 * (1.0 - 1e-6));
        let apart = |dirs: &[DVec3], n: DVec3| {
            dirs.iter()
                .all(|d| d.dot(n).abs() < 2f64.to_radians().cos())
        };
        for (area, n) in faces {
            if area < least || dirs.len() >= 2 * FACE_DIRECTIONS {
                break;
            }
            if apart(&dirs, n) {
                dirs.push(n);
            }
        }
        // And the directions from the centroid to its farthest corners (a crystal's tips).
        let centre = self.rough.solid.centroid();
        let mut tips: Vec<(f64, DVec3)> = self
            .rough
            .solid
            .vertices()
            .iter()
            .map(|v| (v.distance(centre), (*v - centre).normalize()))
            .collect();
        tips.sort_by(|a, b| b.0.total_cmp(&a.0));
        let least = tips
            .get(FACE_DIRECTIONS.saturating_sub(1))
            .map_or(0.0, |t| t.0 * (1.0 - 1e-6));
        let cap = dirs.len() + 2 * FACE_DIRECTIONS;
        for (d, n) in tips {
            if d < least || dirs.len() >= cap {
                break;
            }
            if apart(&dirs, n) {
                dirs.push(n);
            }
        }
        for n in directions(self.frame) {
            if apart(&dirs, n) {
                dirs.push(n);
            }
        }
        dirs
    }

    /// Refine a saw cut of the piece of centroid `centre` whose stone's room is `room` (value
    /// `value`): the offset by golden section within `step` either side, then the normal by
    /// tilts of 12°, 6°, 3° and 1.5° about two axes across it.
    pub(super) fn refine(
        &self,
        room: &Polyhedron,
        centre: DVec3,
        u: DVec3,
        c: f64,
        step: f64,
        value: f64,
    ) -> (DVec3, f64, f64) {
        let (mut u, mut c, mut best) = (u, c, value);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut lo, mut hi) = (c - step, c + step);
        let mut x1 = hi - g * (hi - lo);
        let mut x2 = lo + g * (hi - lo);
        let mut f1 = self.split_value(room, u, x1);
        let mut f2 = self.split_value(room, u, x2);
        for _ in 0..6 {
            if f1 >= f2 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = hi - g * (hi - lo);
                f1 = self.split_value(room, u, x1);
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = lo + g * (hi - lo);
                f2 = self.split_value(room, u, x2);
            }
        }
        for (x, f) in [(x1, f1), (x2, f2)] {
            if f > best {
                (c, best) = (x, f);
            }
        }
        for deg in [12.0f64, 6.0, 3.0, 1.5] {
            // Axes across the normal taken from the rough's frame (so a turned rough tilts
            // the same way).
            let e = [
                self.frame * DVec3::X,
                self.frame * DVec3::Y,
                self.frame * DVec3::Z,
            ];
            let k = e
                .iter()
                .copied()
                .min_by(|p, q| p.dot(u).abs().total_cmp(&q.dot(u).abs()))
                .unwrap_or(DVec3::X);
            let a = (k - k.dot(u) * u).normalize();
            let b = u.cross(a);
            let tilts: Vec<DVec3> = [a, -a, b, -b]
                .iter()
                .map(|w| DQuat::from_axis_angle(*w, deg.to_radians()) * u)
                .collect();
            // The plane turned about its point nearest the piece's centroid.
            let foot = centre + (c - u.dot(centre)) * u;
            let tried: Vec<(DVec3, f64, f64)> = tilts
                .par_iter()
                .map(|t| {
                    let ct = t.dot(foot);
                    (*t, ct, self.split_value(room, *t, ct))
                })
                .collect();
            for (t, ct, f) in tried {
                if f > best {
                    (u, c, best) = (t, ct, f);
                }
            }
        }
        (u, c, best)
    }
}
