//! One more half-space on a solid ([`Polyhedron::cut_by`]): this solid's own faces clipped by
//! one plane, instead of a box clipped by every plane again (a rough's piece sawn, a stone's
//! room cut by a saw plane: hundreds of planes, one new).

use super::{clip, kept_planes, welded, Face, Polyhedron};
use crate::error::Result;
use crate::geometry::FacetPlane;

impl Polyhedron {
    /// This solid cut by the half-space `extra` (`normal·x <= offset`): the solid
    /// [`Polyhedron::from_planes_pruned`] makes of this solid's facet planes followed by
    /// `extra` (the same planes kept, in the same order, the same errors), its vertices equal
    /// to rounding. Where a face would be pruned as a sliver (an area below `1e-10` of the
    /// squared size), or `extra` is not a valid plane, the answer is
    /// [`Polyhedron::from_planes_pruned`]'s itself.
    ///
    /// ```
    /// use facetlab::geometry::{DVec3, FacetPlane, Polyhedron};
    /// let normals = [DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z];
    /// let mut planes: Vec<FacetPlane> = normals
    ///     .iter()
    ///     .enumerate()
    ///     .map(|(i, n)| FacetPlane::new(*n, 0.5, format!("f{i}"), "side"))
    ///     .collect();
    /// let cube = Polyhedron::from_planes(&planes).unwrap();
    /// // Sawn through a corner (x + y + z <= 1): the cube less a tetrahedron of legs 1/2.
    /// let saw = FacetPlane::new(DVec3::ONE.normalize(), 1.0 / 3f64.sqrt(), "saw", "saw");
    /// let sawn = cube.cut_by(&saw).unwrap();
    /// planes.push(saw);
    /// let again = Polyhedron::from_planes_pruned(&planes).unwrap();
    /// assert_eq!(sawn.facets().len(), again.facets().len());
    /// assert!((sawn.volume() - again.volume()).abs() < 1e-12);
    /// assert!((sawn.volume() - (1.0 - 1.0 / 48.0)).abs() < 1e-12);
    /// ```
    pub fn cut_by(&self, extra: &FacetPlane) -> Result<Polyhedron> {
        let mut planes = self.facet_planes();
        planes.push(extra.clone());
        let p = &extra.plane;
        if !(p.normal.is_finite() && p.offset.is_finite()) {
            return Polyhedron::from_planes_pruned(&planes);
        }
        let mut faces: Vec<Face> = self
            .facets
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let poly = f.vertices.iter().map(|&v| self.vertices[v]).collect();
                Face::new(Some(i), f.plane.normal, poly)
            })
            .collect();
        let mut buffer = Vec::new();
        clip(&mut faces, p, planes.len() - 1, &mut buffer);
        let keep = kept_planes(&faces);
        if faces.is_empty() || keep.len() != faces.len() {
            // Nothing left, or a sliver face pruned: the full construction says what it is.
            return Polyhedron::from_planes_pruned(&planes);
        }
        // The planes kept, renumbered in order, and each face's source with them.
        let mut at = vec![usize::MAX; planes.len()];
        for (n, &k) in keep.iter().enumerate() {
            at[k] = n;
        }
        for f in &mut faces {
            f.source = f.source.map(|k| at[k]);
        }
        let kept: Vec<FacetPlane> = keep.iter().map(|&k| planes[k].clone()).collect();
        welded(&faces, &kept)
    }
}

#[cfg(test)]
mod tests {
    use crate::geometry::{DVec3, FacetPlane, Polyhedron};
    use crate::testkit::octahedron_planes;
    use rand::{Rng, SeedableRng};

    /// Against the full construction: random planes through a many-faced solid (an
    /// octahedron with its corners cut), each the same facets in the same order, the same
    /// volume and the same vertices to rounding; a plane missing the solid leaves it whole,
    /// and one cutting it all away is the same error. (Vertices agree within 1e-10 of the
    /// solid's unit size: a crossing computed from another polygon rounds differently.)
    #[test]
    fn one_plane_agrees_with_the_full_construction() {
        let mut planes = octahedron_planes(1.0);
        for (i, n) in [
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::NEG_X,
            DVec3::NEG_Y,
            DVec3::NEG_Z,
        ]
        .iter()
        .enumerate()
        {
            planes.push(FacetPlane::new(*n, 0.8, format!("tip{i}"), "tip"));
        }
        let solid = Polyhedron::from_planes(&planes).unwrap();
        let mut rng = rand::rngs::SmallRng::seed_from_u64(7);
        let mut cut = 0;
        for k in 0..200 {
            let n = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize();
            let d = rng.random_range(-0.9..0.9);
            let extra = FacetPlane::new(n, d, format!("saw{k}"), "saw");
            let mut all = solid.facet_planes();
            all.push(extra.clone());
            let full = Polyhedron::from_planes_pruned(&all);
            let one = solid.cut_by(&extra);
            match (full, one) {
                (Ok(a), Ok(b)) => {
                    let names = |p: &Polyhedron| -> Vec<String> {
                        p.facets().iter().map(|f| f.name.clone()).collect()
                    };
                    assert_eq!(names(&a), names(&b), "plane {k}");
                    assert!((a.volume() - b.volume()).abs() < 1e-12, "plane {k}");
                    for v in b.vertices() {
                        let near = a
                            .vertices()
                            .iter()
                            .map(|w| w.distance(*v))
                            .fold(f64::MAX, f64::min);
                        assert!(
                            near < 1e-10,
                            "plane {k}: a vertex {near} from the full one's"
                        );
                    }
                    if b.volume() < solid.volume() - 1e-9 {
                        cut += 1;
                    }
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
                (a, b) => panic!(
                    "plane {k}: full {:?}, one clip {:?}",
                    a.map(|p| p.volume()),
                    b.map(|p| p.volume())
                ),
            }
        }
        // The planes drawn do cut it, most of them.
        assert!(cut > 100, "{cut} of 200 planes cut the solid");
    }
}
