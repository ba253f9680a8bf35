//! Helpers for the family tests: building with a few overrides, tier counts, symmetry of the
//! facet plane set, widths measured on the solid, and parameter sweeps.

use crate::cut::{family, Cut, Unit};
use crate::error::Result;
use crate::geometry::{DVec3, Plane};
use std::collections::BTreeMap;

/// Build `fam` with `kv` overriding the defaults.
pub fn cut(fam: &str, kv: &[(&str, f64)]) -> Result<Cut> {
    let v: BTreeMap<String, f64> = kv.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    Cut::from_family(fam, fam, &v)
}

/// Build or panic with the error.
pub fn ok(fam: &str, kv: &[(&str, f64)]) -> Cut {
    cut(fam, kv).unwrap_or_else(|e| panic!("{fam} {kv:?}: {e}"))
}

/// Facet count of `tier` (all sides).
pub fn count(c: &Cut, tier: &str) -> usize {
    c.solid.facets().iter().filter(|f| f.tier == tier).count()
}

/// Whether the plane set maps onto itself under the linear map `m` (a mirror or rotation that
/// fixes the origin): every image plane equals some plane of the cut within 1e-9.
pub fn symmetric_under(c: &Cut, m: impl Fn(DVec3) -> DVec3) -> bool {
    let planes: Vec<Plane> = c.solid.facets().iter().map(|f| f.plane).collect();
    planes.iter().all(|p| {
        let n = m(p.normal);
        planes
            .iter()
            .any(|q| q.normal.distance(n) < 1e-9 && (q.offset - p.offset).abs() < 1e-9)
    })
}

/// Mirror x → −x.
pub fn flip_x(v: DVec3) -> DVec3 {
    DVec3::new(-v.x, v.y, v.z)
}

/// Mirror y → −y.
pub fn flip_y(v: DVec3) -> DVec3 {
    DVec3::new(v.x, -v.y, v.z)
}

/// (min, max) corner of the facet named `name`.
pub fn facet_extent(c: &Cut, name: &str) -> (DVec3, DVec3) {
    let i = c
        .solid
        .facets()
        .iter()
        .position(|f| f.name == name)
        .unwrap_or_else(|| panic!("no facet {name}"));
    let pts = c.solid.facet_polygon(i);
    let lo = pts
        .iter()
        .fold(DVec3::splat(f64::INFINITY), |a, p| a.min(*p));
    let hi = pts
        .iter()
        .fold(DVec3::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
    (lo, hi)
}

/// Table width across the stone (y) over the stone's width.
pub fn table_width(c: &Cut) -> f64 {
    let (lo, hi) = facet_extent(c, "table");
    let (slo, shi) = c.solid.bounding_box();
    (hi.y - lo.y) / (shi.y - slo.y)
}

/// Length over width of the bounding box.
pub fn bbox_ratio(c: &Cut) -> f64 {
    let (lo, hi) = c.solid.bounding_box();
    (hi.x - lo.x) / (hi.y - lo.y)
}

/// Angle (degrees to the girdle plane) of the facet named `name`.
pub fn angle_of(c: &Cut, name: &str) -> f64 {
    let f = c
        .solid
        .facets()
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no facet {name}"));
    crate::geometry::facet_angle_deg(f.plane.normal)
}

/// Build the fancy shape `fam` (oval, pear, marquise: an outline with a pointed or round end)
/// at length/width `lw`, table `t`, crown angle `ca`, pavilion angle `pa` and girdle `girdle`
/// (`None`: the family's default, 0.025), and check what every such family promises: its
/// length over width, its table's width, the crown angle on the bezel across the width
/// (`bezel-3`), the pavilion angle, and the total depth girdle + ((1 − t)·tan ca + tan pa)/2.
pub fn fancy_measured(fam: &str, lw: f64, t: f64, ca: f64, pa: f64, girdle: Option<f64>) -> Cut {
    let mut kv = vec![
        ("length_width", lw),
        ("table", t),
        ("crown_angle", ca),
        ("pavilion_angle", pa),
    ];
    kv.extend(girdle.map(|g| ("girdle", g)));
    let c = ok(fam, &kv);
    assert!(
        (bbox_ratio(&c) - lw).abs() < 1e-9,
        "{fam}: length/width {}",
        bbox_ratio(&c)
    );
    assert!(
        (table_width(&c) - t).abs() < 1e-9,
        "{fam}: table {}",
        table_width(&c)
    );
    assert!(
        (angle_of(&c, "bezel-3") - ca).abs() < 1e-9,
        "{fam}: crown angle"
    );
    let p = c.proportions();
    assert!(
        (p.pavilion_angle - pa).abs() < 1e-9,
        "{fam}: pavilion angle"
    );
    let g = girdle.unwrap_or(0.025);
    assert!((p.girdle - g).abs() < 1e-9, "{fam}: girdle {}", p.girdle);
    let depth = g + ((1.0 - t) * ca.to_radians().tan() + pa.to_radians().tan()) / 2.0;
    assert!(
        (p.total_depth - depth).abs() < 1e-9,
        "{fam}: depth {} vs {depth}",
        p.total_depth
    );
    c
}

/// `n + 1` values from `min` to `max`, both included exactly (whole numbers for counts).
fn grid(min: f64, max: f64, n: usize, unit: Unit) -> Vec<f64> {
    if unit == Unit::Count {
        return (min as i64..=max as i64).map(|v| v as f64).collect();
    }
    (0..=n)
        .map(|i| {
            if i == n {
                max
            } else {
                min + (max - min) * i as f64 / n as f64
            }
        })
        .collect()
}

/// Every combination of `crown_angle` × `pavilion_angle` on an (n+1)² grid over their ranges,
/// other parameters at their defaults, builds with every facet.
pub fn sweep_main_angles(fam: &str, n: usize) {
    let f = family(fam).unwrap();
    let (ca, pa) = (
        f.param("crown_angle").unwrap(),
        f.param("pavilion_angle").unwrap(),
    );
    for c in grid(ca.min, ca.max, n, ca.unit) {
        for p in grid(pa.min, pa.max, n, pa.unit) {
            ok(fam, &[("crown_angle", c), ("pavilion_angle", p)]);
        }
    }
}

/// Each parameter alone across its whole range (others at defaults) builds with every facet;
/// returns the number of builds.
pub fn sweep_each(fam: &str, n: usize) -> usize {
    let f = family(fam).unwrap();
    let mut builds = 0;
    for p in f.params {
        for v in grid(p.min, p.max, n, p.unit) {
            if p.key == "girdle_facets" && !(v as usize).is_multiple_of(16) {
                continue;
            }
            ok(fam, &[(p.key, v)]);
            builds += 1;
        }
    }
    builds
}

/// Values just outside every parameter's range (and NaN) are errors naming the key.
pub fn out_of_range_named(fam: &str) {
    let f = family(fam).unwrap();
    for p in f.params {
        let span = (p.max - p.min).max(1.0);
        for v in [p.min - span, p.max + span, f64::NAN] {
            let e = cut(fam, &[(p.key, v)])
                .expect_err(&format!("{fam} {}={v} should fail", p.key))
                .to_string();
            assert!(e.starts_with(&format!("{}:", p.key)), "{fam}: {e}");
            assert!(!e.contains('\n'), "{e}");
        }
    }
}

/// Assert the tier counts of a brilliant with `culet` culets (0 or 1): 1 table, 8 bezels,
/// 8 stars, 16 upper halves, 16 girdle facets, 8 pavilion mains, 16 lower halves (57 + 16
/// facets and the culet).
pub fn assert_brilliant_tiers(c: &Cut, culet: usize) {
    let want = [
        ("table", 1),
        ("bezel", 8),
        ("star", 8),
        ("upper-half", 16),
        ("girdle", 16),
        ("pavilion-main", 8),
        ("lower-half", 16),
        ("culet", culet),
    ];
    for (tier, n) in want {
        assert_eq!(count(c, tier), n, "{tier}");
    }
    assert_eq!(c.solid.facets().len(), 57 + culet + 16);
}
