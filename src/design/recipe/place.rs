//! How deep each placement cuts a tier: centre point, meet, depth, girdle, table.

use super::build::{tier_err, Carved, Resolved};
use super::{Place, Recipe, Side};
use crate::error::Result;
use crate::geometry::{outline_size, DVec3, Plane};
use std::collections::BTreeMap;

impl Recipe {
    /// The depth tier `i` is cut to.
    pub(super) fn depth(&self, i: usize, r: &Resolved, c: &Carved) -> Result<f64> {
        let t = &self.tiers[i];
        let name = &t.name;
        let d = match &t.place {
            Place::Depth(d) | Place::Scale(d) => {
                if !d.is_finite() {
                    return Err(tier_err(name, "depth must be a finite number"));
                }
                *d
            }
            Place::Centre => {
                let Some(side) = r.side else {
                    return Err(tier_err(
                        name,
                        "a girdle tier has no centre point; place it by depth",
                    ));
                };
                let down = side == Side::Pavilion;
                let bounds: Vec<f64> = c
                    .planes
                    .iter()
                    .filter(|p| {
                        if down {
                            p.normal.z < -1e-12
                        } else {
                            p.normal.z > 1e-12
                        }
                    })
                    .map(|p| p.offset / p.normal.z)
                    .collect();
                let z = if bounds.is_empty() {
                    if i == 0 {
                        if down {
                            -1.0
                        } else {
                            1.0
                        }
                    } else {
                        return Err(tier_err(
                            name,
                            format!(
                                "there is no centre point on the {} yet (nothing cut there meets the axis); place {name} by depth or scale",
                                side.name()
                            ),
                        ));
                    }
                } else if down {
                    bounds.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                } else {
                    bounds.iter().copied().fold(f64::INFINITY, f64::min)
                };
                let p = DVec3::new(0.0, 0.0, z);
                r.normals
                    .iter()
                    .map(|n| n.dot(p))
                    .fold(f64::NEG_INFINITY, f64::max)
            }
            Place::Meet(tiers) => {
                if i == 0 {
                    return Err(tier_err(
                        name,
                        "is cut first and has nothing to meet: anchor it with depth, scale or centre = true",
                    ));
                }
                if tiers.is_empty() {
                    return Err(tier_err(name, "meet names no tiers"));
                }
                let mut want: BTreeMap<usize, usize> = BTreeMap::new();
                for m in tiers {
                    match self.tiers[..i].iter().position(|u| &u.name == m) {
                        Some(j) => *want.entry(j).or_default() += 1,
                        None => {
                            return Err(tier_err(
                                name,
                                format!("meet names {m}, which is not a tier cut before {name}"),
                            ))
                        }
                    }
                }
                let tol = c.tol();
                let v: Vec<DVec3> = c
                    .points()
                    .into_iter()
                    .map(|(_, p)| p)
                    .filter(|p| want.iter().all(|(&j, &m)| c.on_tier(j, *p, tol) >= m))
                    .collect();
                if v.is_empty() {
                    let first = *want.keys().next().unwrap_or(&0);
                    let mut meets: Vec<&str> = Vec::new();
                    for (_, p) in c.points() {
                        if c.on_tier(first, p, tol) == 0 {
                            continue;
                        }
                        for (j, u) in self.tiers[..i].iter().enumerate() {
                            if j != first
                                && c.on_tier(j, p, tol) > 0
                                && !meets.contains(&u.name.as_str())
                            {
                                meets.push(&u.name);
                            }
                        }
                    }
                    let hint = if meets.is_empty() {
                        String::new()
                    } else {
                        format!(
                            " ({} meets {} there)",
                            self.tiers[first].name,
                            meets.join(", ")
                        )
                    };
                    return Err(tier_err(
                        name,
                        format!(
                            "meet {}: these tiers do not meet on the stone cut so far{hint}",
                            tiers.join("-")
                        ),
                    ));
                }
                r.normals
                    .iter()
                    .map(|n| {
                        v.iter()
                            .map(|p| n.dot(*p))
                            .fold(f64::NEG_INFINITY, f64::max)
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
            }
            Place::Girdle(th) => {
                let Some(side) = r.side.filter(|_| r.tilt > 0.0) else {
                    return Err(tier_err(
                        name,
                        "a girdle thickness places a sloping crown or pavilion tier, not a girdle, table or culet",
                    ));
                };
                if !(th.is_finite() && *th >= 0.0 && *th < 1.0) {
                    return Err(tier_err(
                        name,
                        format!("girdle {th}: a thickness is a fraction of the width, 0 to 1"),
                    ));
                }
                let tol = c.tol();
                let girdle: Vec<usize> = (0..c.planes.len())
                    .filter(|&k| c.planes[k].normal.z.abs() < 1e-12)
                    .collect();
                if girdle.is_empty() {
                    return Err(tier_err(
                        name,
                        format!("a girdle thickness needs a girdle tier (90°) cut before {name}"),
                    ));
                }
                let pts: Vec<DVec3> = c
                    .points()
                    .into_iter()
                    .filter(|(k, _)| girdle.contains(k))
                    .map(|(_, p)| p)
                    .collect();
                let other: Vec<f64> = pts
                    .iter()
                    .filter(|p| {
                        c.planes.iter().any(|pl| {
                            let facing = if side == Side::Crown {
                                pl.normal.z < -1e-12
                            } else {
                                pl.normal.z > 1e-12
                            };
                            facing && pl.distance(**p).abs() <= tol
                        })
                    })
                    .map(|p| p.z)
                    .collect();
                if other.is_empty() {
                    let o = if side == Side::Crown {
                        "pavilion"
                    } else {
                        "crown"
                    };
                    return Err(tier_err(
                        name,
                        format!("a girdle thickness is measured from the {o}; cut the {o} before {name}"),
                    ));
                }
                let w = outline_size(&pts).1;
                let target = if side == Side::Crown {
                    other.iter().copied().fold(f64::NEG_INFINITY, f64::max) + th * w
                } else {
                    other.iter().copied().fold(f64::INFINITY, f64::min) - th * w
                };
                r.normals
                    .iter()
                    .map(|n| {
                        let m = pts
                            .iter()
                            .map(|p| n.x * p.x + n.y * p.y)
                            .fold(f64::NEG_INFINITY, f64::max);
                        target * n.z + m
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
            }
            Place::Table(w) => {
                if !(r.tilt == 0.0 && r.side == Some(Side::Crown)) {
                    return Err(tier_err(
                        name,
                        "a table width places a flat crown tier (angle 0)",
                    ));
                }
                if !(w.is_finite() && *w > 0.0 && *w < 1.0) {
                    return Err(tier_err(
                        name,
                        format!(
                            "table {w}: a table width is a fraction of the width, between 0 and 1"
                        ),
                    ));
                }
                table_height(name, *w, c)?
            }
        };
        Ok(d)
    }
}

/// The height of a table plane that leaves a table `w` of the width.
fn table_height(name: &str, w: f64, c: &Carved) -> Result<f64> {
    if c.block.open().iter().any(|n| n.z > 0.5) {
        return Err(tier_err(
            name,
            format!(
                "a table width needs the crown closed above it; cut the crown tiers before {name}"
            ),
        ));
    }
    let pts = c.points();
    if pts.is_empty() {
        return Err(tier_err(name, "there is no stone yet to cut a table on"));
    }
    let all: Vec<DVec3> = pts.iter().map(|(_, p)| *p).collect();
    let (lo, hi) = all.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(a, b), p| (a.min(*p), b.max(*p)),
    );
    let along_x = hi.x - lo.x <= hi.y - lo.y;
    let full = if along_x { hi.x - lo.x } else { hi.y - lo.y };
    let girdle_top = pts
        .iter()
        .filter(|(k, _)| c.planes[*k].normal.z.abs() < 1e-12)
        .map(|(_, p)| p.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let z_lo = if girdle_top.is_finite() {
        girdle_top
    } else {
        lo.z
    };
    let width = |h: f64| table_width(c, h, along_x, full);
    let most = width(z_lo);
    if w > most {
        return Err(tier_err(
            name,
            format!(
                "a table of {:.1} % of the width does not fit above the girdle (at most {:.1} %)",
                w * 100.0,
                most * 100.0
            ),
        ));
    }
    let (mut a, mut b) = (z_lo, hi.z);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if width(m) > w {
            a = m;
        } else {
            b = m;
        }
    }
    Ok(0.5 * (a + b))
}

/// The width of a table cut at height `h` on `c`, along x (else y), as a fraction of `full`.
fn table_width(c: &Carved, h: f64, along_x: bool, full: f64) -> f64 {
    let mut b = c.block.clone();
    let k = b.cut(Plane {
        normal: DVec3::Z,
        offset: h,
    });
    let f = b.face(k);
    if f.len() < 3 {
        return 0.0;
    }
    let (a, z) = f
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, z), p| {
            let v = if along_x { p.x } else { p.y };
            (a.min(v), z.max(v))
        });
    (z - a) / full
}

/// The table width (a fraction of the width) a flat crown plane at height `h` leaves on `c`.
pub(super) fn table_fraction(c: &Carved, h: f64) -> f64 {
    let pts = c.points();
    let (lo, hi) = pts.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(a, b), (_, p)| (a.min(*p), b.max(*p)),
    );
    let along_x = hi.x - lo.x <= hi.y - lo.y;
    let full = if along_x { hi.x - lo.x } else { hi.y - lo.y };
    table_width(c, h, along_x, full)
}
