//! The crystal's modes and boundary conditions against closed forms, energy conservation and
//! an independent 4×4 transfer-matrix (Berreman) computation written here.

use super::boundary::jones_stokes;
use super::*;
use crate::optics::fresnel;
use crate::optics::polarization::Stokes;
use glam::{DVec3, DVec4};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

fn unit(rng: &mut SmallRng) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.random::<f64>() * 2.0 - 1.0,
            rng.random::<f64>() * 2.0 - 1.0,
            rng.random::<f64>() * 2.0 - 1.0,
        );
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            return v / l;
        }
    }
}

/// A random crystal: indices 1.4–2.7 with birefringence ±0.005–0.3 (both signs, and
/// strong walk-off), random axis. (Below that the two modes' wave vectors nearly coincide
/// and an eigenvalue computation, Berreman's included, loses half its digits separating
/// them; the isotropic limit is checked against Fresnel's equations instead.)
fn crystal(rng: &mut SmallRng) -> Crystal {
    let n_o = 1.4 + 1.3 * rng.random::<f64>();
    let b = 0.005 + 0.295 * rng.random::<f64>();
    let n_e = if rng.random::<bool>() {
        n_o + b
    } else {
        n_o - b
    };
    Crystal::new(n_o, n_e.max(1.3), unit(rng))
}

// ---- An independent Berreman 4×4 computation -------------------------------------------

/// Berreman's frame: z along the facet normal (from the incident side into the other), x
/// along the tangential wave vector, y = z × x. Fields ψ = (Ex, Hy, Ey, −Hx) (units k₀ = 1,
/// H = k × E), dψ/dz = i Δ ψ.
struct Frame3 {
    x: DVec3,
    y: DVec3,
    z: DVec3,
}

impl Frame3 {
    fn new(z: DVec3, k: DVec3) -> Frame3 {
        let kt = k - z * k.dot(z);
        let x = if kt.length() > 1e-12 {
            kt.normalize()
        } else {
            z.any_orthonormal_vector()
        };
        Frame3 {
            x,
            y: z.cross(x),
            z,
        }
    }
    fn local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
    }
}

/// Berreman's Δ for dielectric tensor `e` (in the frame) and tangential wave number `xi`,
/// from Maxwell's curl equations with ∂/∂x = iξ, ∂/∂y = 0 (eliminating Ez and Hz):
/// q Ex = −ξε31/ε33 Ex + (1 − ξ²/ε33) Hy − ξε32/ε33 Ey, q Hy = (ε11 − ε13ε31/ε33) Ex −
/// ξε13/ε33 Hy + (ε12 − ε13ε32/ε33) Ey, q Ey = −Hx, q(−Hx) = (ε21 − ε23ε31/ε33) Ex −
/// ξε23/ε33 Hy + (ε22 − ξ² − ε23ε32/ε33) Ey.
fn delta(e: [[f64; 3]; 3], xi: f64) -> [[f64; 4]; 4] {
    let e33 = e[2][2];
    [
        [
            -xi * e[2][0] / e33,
            1.0 - xi * xi / e33,
            -xi * e[2][1] / e33,
            0.0,
        ],
        [
            e[0][0] - e[0][2] * e[2][0] / e33,
            -xi * e[0][2] / e33,
            e[0][1] - e[0][2] * e[2][1] / e33,
            0.0,
        ],
        [0.0, 0.0, 0.0, 1.0],
        [
            e[1][0] - e[1][2] * e[2][0] / e33,
            -xi * e[1][2] / e33,
            e[1][1] - xi * xi - e[1][2] * e[2][1] / e33,
            0.0,
        ],
    ]
}

/// Coefficients `[1, c3, c2, c1, c0]` of det(qI − Δ) = q⁴ + c3 q³ + c2 q² + c1 q + c0 by
/// Faddeev–LeVerrier.
fn charpoly(a: [[f64; 4]; 4]) -> [f64; 5] {
    let mul = |x: &[[f64; 4]; 4], y: &[[f64; 4]; 4]| {
        let mut z = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                for k in 0..4 {
                    z[i][j] += x[i][k] * y[k][j];
                }
            }
        }
        z
    };
    let mut c = [1.0, 0.0, 0.0, 0.0, 0.0];
    let mut m = [[0.0; 4]; 4]; // M_0 = 0
    for k in 1..=4 {
        // M_k = A M_{k−1} + c_{n−k+1} I ; c_{n−k} = −tr(A M_k)/k
        let mut mk = mul(&a, &m);
        for (i, row) in mk.iter_mut().enumerate() {
            row[i] += c[k - 1];
        }
        let am = mul(&a, &mk);
        let tr: f64 = (0..4).map(|i| am[i][i]).sum();
        c[k] = -tr / k as f64;
        m = mk;
    }
    c
}

/// The four complex roots of a monic quartic, by the Durand–Kerner iteration, polished.
fn quartic_roots(c: [f64; 5]) -> [C; 4] {
    let p = |z: C| {
        let mut v = C::real(1.0);
        for &ck in &c[1..] {
            v = v * z + C::real(ck);
        }
        v
    };
    let scale = c.iter().skip(1).map(|x| x.abs()).fold(1.0f64, f64::max);
    let mut z = [0, 1, 2, 3].map(|k| {
        let base = C::new(0.4, 0.9);
        let mut w = C::real(scale);
        for _ in 0..k {
            w = w * base;
        }
        w
    });
    for _ in 0..2000 {
        let mut moved = 0.0f64;
        for i in 0..4 {
            let mut den = C::real(1.0);
            for j in 0..4 {
                if i != j {
                    den = den * (z[i] - z[j]);
                }
            }
            let step = p(z[i]) / den;
            z[i] = z[i] - step;
            moved = moved.max(step.norm_sqr());
        }
        if moved < 1e-34 {
            break;
        }
    }
    z
}

/// det(Δ − qI) by Gaussian elimination (partial pivoting) of the matrix itself.
fn det_shifted(d: [[f64; 4]; 4], q: C) -> C {
    let mut m: [[C; 4]; 4] = std::array::from_fn(|i| {
        std::array::from_fn(|j| C::real(d[i][j]) - if i == j { q } else { C::default() })
    });
    let mut det = C::real(1.0);
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&i, &j| m[i][c].norm_sqr().total_cmp(&m[j][c].norm_sqr()))
            .unwrap();
        if p != c {
            m.swap(c, p);
            det = -det;
        }
        det = det * m[c][c];
        if m[c][c].norm_sqr() == 0.0 {
            return C::default();
        }
        for r in c + 1..4 {
            let f = m[r][c] / m[c][c];
            let pivot_row = m[c];
            for (x, v) in m[r].iter_mut().zip(pivot_row).skip(c) {
                *x = *x - f * v;
            }
        }
    }
    det
}

/// An eigenvalue polished by Newton's method on det(Δ − qI) evaluated from the matrix (the
/// characteristic polynomial's coefficients lose half the digits of two close roots).
fn polish(d: [[f64; 4]; 4], mut q: C) -> C {
    for _ in 0..20 {
        let h = 1e-6 * (1.0 + q.norm_sqr().sqrt());
        let f = det_shifted(d, q);
        let df = (det_shifted(d, q + C::real(h)) - det_shifted(d, q - C::real(h))).scale(0.5 / h);
        if df.norm_sqr() == 0.0 {
            break;
        }
        let step = f / df;
        q = q - step;
        if step.norm_sqr() < 1e-34 * (1.0 + q.norm_sqr()) {
            break;
        }
    }
    q
}

fn det3(m: [[C; 3]; 3]) -> C {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// A null vector of the rank-3 matrix Δ − qI: the largest column of its adjugate.
fn eigvec(d: [[f64; 4]; 4], q: C) -> [C; 4] {
    let m: [[C; 4]; 4] = std::array::from_fn(|i| {
        std::array::from_fn(|j| C::real(d[i][j]) - if i == j { q } else { C::default() })
    });
    let mut best = ([C::default(); 4], -1.0);
    for col in 0..4 {
        // Column `col` of adj(M): cofactors C_{col, i} for i = 0..4.
        let v: [C; 4] = std::array::from_fn(|i| {
            let rows: Vec<usize> = (0..4).filter(|&r| r != col).collect();
            let cols: Vec<usize> = (0..4).filter(|&c| c != i).collect();
            let sub: [[C; 3]; 3] =
                std::array::from_fn(|a| std::array::from_fn(|b| m[rows[a]][cols[b]]));
            let s = if (i + col) % 2 == 0 { 1.0 } else { -1.0 };
            det3(sub).scale(s)
        });
        let n: f64 = v.iter().map(|x| x.norm_sqr()).sum();
        if n > best.1 {
            best = (v, n);
        }
    }
    best.0
}

/// ½ Re(Ex Hy* − Ey Hx*) = ½ Re(ψ1 ψ2* + ψ3 ψ4*): the flux along z.
fn sz(p: &[C; 4]) -> f64 {
    0.5 * ((p[0] * p[1].conj()).re + (p[2] * p[3].conj()).re)
}

/// Plain Gaussian elimination (partial pivoting) for the test's own 4×4 systems.
fn gauss(mut a: [[C; 4]; 4], mut b: [C; 4]) -> [C; 4] {
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&i, &j| a[i][c].norm_sqr().total_cmp(&a[j][c].norm_sqr()))
            .unwrap();
        a.swap(c, p);
        b.swap(c, p);
        for r in 0..4 {
            if r != c {
                let f = a[r][c] / a[c][c];
                let pivot_row = a[c];
                for (x, v) in a[r].iter_mut().zip(pivot_row) {
                    *x = *x - f * v;
                }
                let v = b[c];
                b[r] = b[r] - f * v;
            }
        }
    }
    std::array::from_fn(|i| b[i] / a[i][i])
}

/// A mode in Berreman's frame: q, ψ, and whether it is the ordinary one.
type BMode = (C, [C; 4], bool);

/// A crystal's modes in Berreman's frame: (q, ψ, is ordinary), the two going +z first.
fn berreman_modes(cr: &Crystal, f: &Frame3, xi: f64) -> ([BMode; 2], [BMode; 2]) {
    let c = f.local(cr.axis);
    let (eo, ee) = (cr.n_o * cr.n_o, cr.n_e * cr.n_e);
    let e: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| eo * (i == j) as u8 as f64 + (ee - eo) * c[i] * c[j])
    });
    let d = delta(e, xi);
    let roots = quartic_roots(charpoly(d)).map(|q| polish(d, q));
    let mut up = Vec::new();
    let mut down = Vec::new();
    for q in roots {
        let q = if q.im.abs() < 1e-9 * (1.0 + q.re.abs()) {
            C::real(q.re)
        } else {
            q
        };
        let psi = eigvec(d, q);
        let is_o = ((q * q).re + xi * xi - eo).abs() < 1e-7 && (q * q).im.abs() < 1e-7;
        let forward = if q.im == 0.0 {
            sz(&psi) > 0.0
        } else {
            q.im > 0.0
        };
        if forward {
            up.push((q, psi, is_o));
        } else {
            down.push((q, psi, is_o));
        }
    }
    assert_eq!((up.len(), down.len()), (2, 2), "{roots:?}");
    ([up[0], up[1]], [down[0], down[1]])
}

/// Air's s and p waves in Berreman's frame going along ±z: s has E = ŷ, p has E = k̂ × ŷ.
fn air_modes(xi: f64, sign: f64) -> (C, [C; 4], [C; 4]) {
    let g = 1.0 - xi * xi;
    let q = if g >= 0.0 {
        C::real(sign * g.sqrt())
    } else {
        C::new(0.0, sign * (-g).sqrt())
    };
    // s: E = (0,1,0), H = k × E = (−q, 0, ξ): ψ = (0, 0, 1, q).
    let s = [C::default(), C::default(), C::real(1.0), q];
    // p: E = k × ŷ = (−q, 0, ξ), H = k × E = (0, −(q² + ξ²), 0) = (0, −1, 0): ψ = (−q, −1, 0, 0).
    let p = [-q, C::real(-1.0), C::default(), C::default()];
    (q, s, p)
}

/// Berreman's answer for light inside in mode `mode` (wave vector `k`) meeting a facet of
/// outward normal `n`: reflected powers per mode (o, e), transmitted power, and the
/// transmitted Jones vector (s, p).
fn berreman_meet(cr: &Crystal, k: DVec3, mode: WaveMode, n: DVec3) -> ([f64; 2], f64, (C, C)) {
    let f = Frame3::new(n, k);
    let xi = f.local(k).x;
    let (up, down) = berreman_modes(cr, &f, xi);
    let want_o = mode == WaveMode::Ordinary;
    let inc = up.iter().find(|m| m.2 == want_o).expect("incident mode");
    let (_, s, p) = air_modes(xi, 1.0);
    let mut a = [[C::default(); 4]; 4];
    let mut b = [C::default(); 4];
    for r in 0..4 {
        a[r] = [down[0].1[r], down[1].1[r], -s[r], -p[r]];
        b[r] = -inc.1[r];
    }
    let x = gauss(a, b);
    let f_in = sz(&inc.1);
    let mut refl = [0.0; 2];
    for (i, m) in down.iter().enumerate() {
        if m.0.im == 0.0 {
            let idx = if m.2 { 0 } else { 1 };
            refl[idx] += x[i].norm_sqr() * -sz(&m.1) / f_in;
        }
    }
    let trans = (x[2].norm_sqr() * sz(&s) + x[3].norm_sqr() * sz(&p)) / f_in;
    let trans = if s[3].im == 0.0 { trans } else { 0.0 };
    // Jones vector scaled to power: the s and p waves have equal flux per amplitude².
    let g = if s[3].im == 0.0 {
        (sz(&s) / f_in).sqrt()
    } else {
        0.0
    };
    (refl, trans, (x[2].scale(g), x[3].scale(g)))
}

/// Berreman's answer for light from air along `d` meeting a facet of outward normal `n`:
/// per incident polarization (s, p): the reflected Jones vector (s, p) scaled to power and
/// the transmitted powers per mode (o, e).
fn berreman_enter(cr: &Crystal, d: DVec3, n: DVec3) -> [((C, C), [f64; 2]); 2] {
    let f = Frame3::new(-n, d);
    let xi = f.local(d).x;
    let (up, _) = berreman_modes(cr, &f, xi);
    let (_, si, pi) = air_modes(xi, 1.0);
    let (_, sr, pr) = air_modes(xi, -1.0);
    let f_in = sz(&si);
    [si, pi].map(|inc| {
        let mut a = [[C::default(); 4]; 4];
        let mut b = [C::default(); 4];
        for r in 0..4 {
            a[r] = [sr[r], pr[r], -up[0].1[r], -up[1].1[r]];
            b[r] = -inc[r];
        }
        let x = gauss(a, b);
        let g = (-sz(&sr) / f_in).sqrt();
        let mut t = [0.0; 2];
        for (i, m) in up.iter().enumerate() {
            let idx = if m.2 { 0 } else { 1 };
            t[idx] += x[2 + i].norm_sqr() * sz(&m.1) / f_in;
        }
        ((x[0].scale(g), x[1].scale(g)), t)
    })
}

fn stokes_of(j: (C, C)) -> Stokes {
    jones_stokes(j.0, j.1)
}

/// Check 1: at random interfaces, axes and incidences (total internal reflection of one or
/// both modes included), every mode's reflected + transmitted power is 1 to 1e-12, and the
/// powers per mode and the light leaving (its Stokes vector) agree with Berreman's 4×4
/// method to 1e-10; the same on entry from outside for s, p and unpolarized light.
#[test]
fn boundary_conditions_agree_with_berreman_and_conserve_energy() {
    let mut rng = SmallRng::seed_from_u64(41);
    let (mut tir, mut half_tir, mut partial, mut checked) = (0, 0, 0, 0);
    let (mut worst_energy, mut worst_berreman) = (0.0f64, 0.0f64);
    for _ in 0..4000 {
        let cr = crystal(&mut rng);
        let n = unit(&mut rng);
        // Inside: a random wave normal heading for the facet.
        let mode = WaveMode::BOTH[rng.random_range(0..2)];
        let w = cr.wave_along(unit(&mut rng), mode);
        if w.ray.dot(n) < 0.05 || w.k.dot(n) < 0.05 {
            continue;
        }
        let m = cr.meet(&w, n).expect("not grazing");
        let total = m.reflected[0].1 + m.reflected[1].1 + m.exit_power;
        assert!((total - 1.0).abs() < 1e-12, "energy {total}");
        worst_energy = worst_energy.max((total - 1.0).abs());
        assert!(m.reflected.iter().all(|r| r.1 >= -1e-15) && m.exit_power >= 0.0);
        let (refl, trans, jones) = berreman_meet(&cr, w.k, mode, n);
        #[allow(clippy::needless_range_loop)]
        for i in 0..2 {
            worst_berreman = worst_berreman.max((refl[i] - m.reflected[i].1).abs());
            assert!(
                (refl[i] - m.reflected[i].1).abs() < 1e-10,
                "{mode:?} reflected {i}: {} vs Berreman {} ({cr:?}, k {}, n {n})",
                m.reflected[i].1,
                refl[i],
                w.k
            );
        }
        assert!(
            (trans - m.exit_power).abs() < 1e-10,
            "{trans} {}",
            m.exit_power
        );
        let sb = stokes_of(jones);
        assert!((sb - m.exit).length() < 1e-10, "{sb} vs {}", m.exit);
        if m.exit_power == 0.0 {
            tir += 1;
        } else {
            partial += 1;
        }
        if m.reflected.iter().any(|r| r.1 == 0.0) {
            // One reflected mode evanescent: that mode totally reflected away.
            half_tir += 1;
        }
        checked += 1;
        // Reflected waves head back into the stone, along their rays.
        for (r, p) in m.reflected {
            if p > 0.0 {
                assert!(r.ray.dot(n) < 0.0 && (r.ray.length() - 1.0).abs() < 1e-12);
                let kt = r.k - n * r.k.dot(n);
                let kt0 = w.k - n * w.k.dot(n);
                assert!((kt - kt0).length() < 1e-12, "phase matching");
            }
        }
    }
    eprintln!(
        "{checked} facets met from inside ({tir} totally reflected, {half_tir} with one mode evanescent): |R + T − 1| ≤ {worst_energy:.1e}, |R − R_Berreman| ≤ {worst_berreman:.1e}"
    );
    assert!(
        checked > 1500 && tir > 500 && partial > 200 && half_tir > 20,
        "{checked} {tir} {partial} {half_tir}"
    );

    // Entry.
    for _ in 0..2000 {
        let cr = crystal(&mut rng);
        let n = unit(&mut rng);
        let d = unit(&mut rng);
        if d.dot(n) > -0.05 {
            continue;
        }
        let b = berreman_enter(&cr, d, n);
        let s_axis = (-n).cross(Frame3::new(-n, d).x);
        for (input, want) in [
            (DVec4::new(1.0, 1.0, 0.0, 0.0), {
                let (j, t) = b[0];
                (stokes_of(j), t)
            }),
            (DVec4::new(1.0, -1.0, 0.0, 0.0), {
                let (j, t) = b[1];
                (stokes_of(j), t)
            }),
            (DVec4::new(1.0, 0.0, 0.0, 0.0), {
                let (js, ts) = b[0];
                let (jp, tp) = b[1];
                (
                    (stokes_of(js) + stokes_of(jp)) * 0.5,
                    [0.5 * (ts[0] + tp[0]), 0.5 * (ts[1] + tp[1])],
                )
            }),
        ] {
            let e = cr.enter(d, n, input, s_axis).expect("entry");
            let total = e.reflected.x + e.transmitted[0].1 + e.transmitted[1].1;
            assert!((total - 1.0).abs() < 1e-12, "entry energy {total}");
            assert!((e.axis - s_axis).length() < 1e-12);
            assert!(
                (e.reflected - want.0).length() < 1e-10,
                "{} vs {}",
                e.reflected,
                want.0
            );
            for m in 0..2 {
                assert!((e.transmitted[m].1 - want.1[m]).abs() < 1e-10);
                let w = e.transmitted[m].0;
                assert!(w.ray.dot(n) < 0.0, "enters");
                assert_eq!(w.mode, WaveMode::BOTH[m]);
            }
        }
    }
}

/// Check 2 (closed forms): the extraordinary index along a direction, the walk-off angle
/// `tan ρ = ½ n(θ)² |1/n_o² − 1/n_e²| sin 2θ` (sapphire's largest ~0.26°, quartz ~0.33°,
/// zircon ~1.7°), the ordinary wave's ray along its wave vector, and each mode's absorption
/// (α_o for the ordinary wave, α_e for the extraordinary one ⊥ ĉ, between them otherwise).
#[test]
fn indices_walk_off_and_absorption_match_closed_forms() {
    let mut rng = SmallRng::seed_from_u64(7);
    for _ in 0..500 {
        let cr = crystal(&mut rng);
        let dir = unit(&mut rng);
        let th = dir.dot(cr.axis).clamp(-1.0, 1.0).acos();
        let ne = 1.0 / ((th.cos() / cr.n_o).powi(2) + (th.sin() / cr.n_e).powi(2)).sqrt();
        let we = cr.wave_along(dir, WaveMode::Extraordinary);
        let wo = cr.wave_along(dir, WaveMode::Ordinary);
        assert!((we.k.length() - ne).abs() < 1e-12);
        assert!((wo.k.length() - cr.n_o).abs() < 1e-12);
        assert!((wo.ray - dir).length() < 1e-12);
        // Walk-off.
        let rho = we.ray.angle_between(we.k);
        let want = (0.5
            * ne
            * ne
            * (1.0 / cr.n_o.powi(2) - 1.0 / cr.n_e.powi(2)).abs()
            * (2.0 * th).sin().abs())
        .atan();
        assert!((rho - want).abs() < 1e-10, "{rho} {want}");
        // The ray lies in the plane of k and ĉ; the fields are ⊥ k (o) and in that plane (e).
        assert!(we.ray.dot(dir.cross(cr.axis)).abs() < 1e-12);
        assert!(wo.field.dot(cr.axis).abs() < 1e-12 && wo.field.dot(dir).abs() < 1e-12);
        assert!(we.field.dot(dir.cross(cr.axis).normalize_or_zero()).abs() < 1e-12);
        // Absorption per mode.
        let (ao, ae) = (0.7, 2.3);
        assert!((cr.absorption(&wo, ao, ae) - ao).abs() < 1e-12);
        let a = cr.absorption(&we, ao, ae);
        assert!(a >= ao - 1e-12 && a <= ae + 1e-12, "{a}");
    }
    // Along ĉ the extraordinary wave is ordinary; across it, E ∥ ĉ with α_e.
    let cr = Crystal::new(1.7682, 1.7600, DVec3::new(0.0, 0.6, 0.8));
    let along = cr.wave_along(cr.axis, WaveMode::Extraordinary);
    assert!((along.k.length() - cr.n_o).abs() < 1e-12);
    let across = cr.wave_along(DVec3::X, WaveMode::Extraordinary);
    assert!((across.k.length() - cr.n_e).abs() < 1e-12);
    assert!((cr.absorption(&across, 0.3, 1.9) - 1.9).abs() < 1e-12);
    // The largest walk-off of sapphire, quartz and zircon (handbook n_ω, n_ε).
    for (n_o, n_e, deg) in [
        (1.768, 1.760, 0.26),
        (1.544, 1.553, 0.33),
        (1.925, 1.984, 1.7),
    ] {
        let cr = Crystal::new(n_o, n_e, DVec3::Z);
        let best = (0..=900)
            .map(|i| {
                let th = (i as f64 / 10.0).to_radians();
                let w = cr.wave_along(DVec3::new(th.sin(), 0.0, th.cos()), WaveMode::Extraordinary);
                w.ray.angle_between(w.k).to_degrees()
            })
            .fold(0.0, f64::max);
        assert!((best - deg).abs() < 0.02 * deg, "{n_o} {n_e}: {best}°");
    }
}

/// At normal incidence with the axis in the facet's plane the modes keep apart: each
/// reflects with `((n − 1)/(n + 1))²` of its own index and converts nothing; and an isotropic
/// crystal (`n_o = n_e`) is Fresnel's equations, phases (Stokes vectors) and all.
#[test]
fn normal_incidence_and_the_isotropic_limit() {
    let cr = Crystal::new(1.768, 1.760, DVec3::X);
    let n = DVec3::Z;
    for mode in WaveMode::BOTH {
        let w = cr.wave_along(DVec3::Z, mode);
        let idx = if mode == WaveMode::Ordinary {
            cr.n_o
        } else {
            cr.n_e
        };
        let r = ((idx - 1.0) / (idx + 1.0)).powi(2);
        let m = cr.meet(&w, n).unwrap();
        assert!((m.reflected[mode.index()].1 - r).abs() < 1e-14);
        assert!(m.reflected[1 - mode.index()].1.abs() < 1e-14);
        assert!((m.exit_power - (1.0 - r)).abs() < 1e-14);
    }
    let e = cr
        .enter(DVec3::NEG_Z, n, DVec4::new(1.0, 0.0, 0.0, 0.0), DVec3::X)
        .unwrap();
    let to = 0.5 * (1.0 - ((cr.n_o - 1.0) / (cr.n_o + 1.0)).powi(2));
    let te = 0.5 * (1.0 - ((cr.n_e - 1.0) / (cr.n_e + 1.0)).powi(2));
    assert!((e.transmitted[0].1 - to).abs() < 1e-14 && (e.transmitted[1].1 - te).abs() < 1e-14);

    // Isotropic limit against optics::fresnel, entering and leaving (TIR included).
    let ri = 2.4173;
    let iso = Crystal::new(ri, ri, DVec3::new(0.3, -0.4, 0.866).normalize());
    for deg in [0.0f64, 10.0, 20.0, 24.0, 30.0, 50.0, 70.0, 85.0] {
        let th = deg.to_radians();
        let inside = DVec3::new(th.sin(), 0.0, th.cos());
        let w = iso.wave_along(inside, WaveMode::Ordinary);
        let m = iso.meet(&w, n).unwrap();
        let f = fresnel(th.cos(), ri, 1.0);
        let r: f64 = m.reflected.iter().map(|r| r.1).sum();
        // The incident o wave is some mix of s and p: its reflectance lies between Rs and Rp,
        // and an s-polarized incident one (axis ⊥ s) reflects exactly Rs.
        assert!(r >= f.r_s.min(f.r_p) - 1e-12 && r <= f.r_s.max(f.r_p) + 1e-12);
        let outside = DVec3::new(th.sin(), 0.0, -th.cos());
        let e = iso
            .enter(outside, n, DVec4::new(1.0, 0.0, 0.0, 0.0), DVec3::Y)
            .unwrap();
        let f = fresnel(th.cos(), 1.0, ri);
        assert!((e.reflected.x - f.reflectance()).abs() < 1e-12, "{deg}");
        assert!((e.reflected.y - 0.5 * (f.r_s - f.r_p)).abs() < 1e-12);
        for v in [
            DVec4::new(1.0, 0.0, 1.0, 0.0),
            DVec4::new(1.0, 0.6, 0.0, 0.8),
        ] {
            let want = f.mueller_reflect().apply(v);
            let got = iso.enter(outside, n, v, e.axis).unwrap().reflected;
            assert!((got - want).length() < 1e-12, "{deg}: {got} {want}");
        }
    }
    // Inside, with the axis ⊥ the plane of incidence (along s) the ordinary wave (E ∝ k × ĉ)
    // is p-polarized and the extraordinary one s-polarized: Rp and Rs, and under TIR
    // nothing leaves.
    let iso = Crystal::new(ri, ri, DVec3::Y);
    for deg in [10.0f64, 20.0, 30.0, 60.0] {
        let th = deg.to_radians();
        let w = iso.wave_along(DVec3::new(th.sin(), 0.0, th.cos()), WaveMode::Extraordinary);
        let m = iso.meet(&w, n).unwrap();
        let f = fresnel(th.cos(), ri, 1.0);
        let r: f64 = m.reflected.iter().map(|r| r.1).sum();
        let wo = iso.wave_along(DVec3::new(th.sin(), 0.0, th.cos()), WaveMode::Ordinary);
        let ro: f64 = iso
            .meet(&wo, n)
            .unwrap()
            .reflected
            .iter()
            .map(|r| r.1)
            .sum();
        assert!((ro - f.r_p).abs() < 1e-12, "{deg}: {ro} {}", f.r_p);
        assert!((r - f.r_s).abs() < 1e-12, "{deg}: {r} {}", f.r_s);
        assert_eq!(m.exit_power == 0.0, f.tir);
    }
}
