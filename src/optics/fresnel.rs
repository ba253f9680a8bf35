//! Snell's law and Fresnel's equations for a plane interface between dielectrics.

use super::polarization::Mueller;
use glam::DVec3;

/// A complex number (only what Fresnel amplitudes need).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Complex {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Complex {
    /// `re + 0i`.
    pub fn real(re: f64) -> Complex {
        Complex { re, im: 0.0 }
    }
    /// `|z|²`.
    pub fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }
    /// Argument in radians.
    pub fn arg(self) -> f64 {
        self.im.atan2(self.re)
    }
    /// `self · conj(other)`.
    pub fn mul_conj(self, o: Complex) -> Complex {
        Complex {
            re: self.re * o.re + self.im * o.im,
            im: self.im * o.re - self.re * o.im,
        }
    }
}

/// Everything about one ray meeting an interface from medium `n_i` into medium `n_t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    /// Cosine of the angle of incidence (≥ 0).
    pub cos_i: f64,
    /// Cosine of the angle of refraction; 0 under total internal reflection.
    pub cos_t: f64,
    /// Total internal reflection.
    pub tir: bool,
    /// Amplitude reflection coefficient, s (perpendicular) component.
    pub rs: Complex,
    /// Amplitude reflection coefficient, p (parallel) component.
    pub rp: Complex,
    /// Amplitude transmission coefficient, s; 0 under TIR.
    pub ts: f64,
    /// Amplitude transmission coefficient, p; 0 under TIR.
    pub tp: f64,
    /// Power reflectance, s.
    pub r_s: f64,
    /// Power reflectance, p.
    pub r_p: f64,
}

impl Interface {
    /// Unpolarized reflectance (Rs + Rp)/2.
    #[inline]
    pub fn reflectance(&self) -> f64 {
        0.5 * (self.r_s + self.r_p)
    }
    /// Power transmittance, s (= 1 − Rs by energy conservation).
    pub fn t_s(&self) -> f64 {
        1.0 - self.r_s
    }
    /// Power transmittance, p.
    pub fn t_p(&self) -> f64 {
        1.0 - self.r_p
    }
    /// s–p phase difference of the reflected wave, arg(rp) − arg(rs), in (−π, π].
    pub fn phase_difference(&self) -> f64 {
        let d = self.rp.arg() - self.rs.arg();
        let two_pi = 2.0 * std::f64::consts::PI;
        let mut d = d % two_pi;
        if d <= -std::f64::consts::PI {
            d += two_pi;
        } else if d > std::f64::consts::PI {
            d -= two_pi;
        }
        d
    }
    /// Mueller matrix of reflection in the s–p frame.
    pub fn mueller_reflect(&self) -> Mueller {
        let c = self.rs.mul_conj(self.rp);
        Mueller::block(
            0.5 * (self.r_s + self.r_p),
            0.5 * (self.r_s - self.r_p),
            c.re,
            c.im,
        )
    }
    /// Mueller matrix of transmission (power, including the beam-area factor) in the s–p frame.
    pub fn mueller_transmit(&self) -> Mueller {
        let (ts, tp) = (self.t_s(), self.t_p());
        Mueller::block(
            0.5 * (ts + tp),
            0.5 * (ts - tp),
            (ts * tp).max(0.0).sqrt(),
            0.0,
        )
    }
}

/// Fresnel's equations for incidence cosine `cos_i` from index `n_i` into index `n_t`.
#[inline]
pub fn fresnel(cos_i: f64, n_i: f64, n_t: f64) -> Interface {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let eta = n_i / n_t;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        // TIR: |rs| = |rp| = 1 with phases (Born & Wolf §1.5.4).
        // With n = n_t/n_i: rs = (cos − i·sqrt(sin² − n²)) / (cos + i·sqrt(sin² − n²)),
        //                   rp = (n²cos − i·sqrt(sin² − n²)) / (n²cos + i·sqrt(sin² − n²)).
        let n = 1.0 / eta;
        let root = (sin2_t - 1.0).sqrt() / eta; // = sqrt(sin²θ − n²)
        let rs = unit_ratio(cos_i, root);
        let rp = unit_ratio(n * n * cos_i, root);
        return Interface {
            cos_i,
            cos_t: 0.0,
            tir: true,
            rs,
            rp,
            ts: 0.0,
            tp: 0.0,
            r_s: 1.0,
            r_p: 1.0,
        };
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let (a, b) = (n_i * cos_i, n_t * cos_t);
    let (c, d) = (n_t * cos_i, n_i * cos_t);
    let rs = (a - b) / (a + b);
    let rp = (c - d) / (c + d);
    let ts = 2.0 * a / (a + b);
    let tp = 2.0 * a / (c + d);
    Interface {
        cos_i,
        cos_t,
        tir: false,
        rs: Complex::real(rs),
        rp: Complex::real(rp),
        ts,
        tp,
        r_s: rs * rs,
        r_p: rp * rp,
    }
}

/// `(x − i·y)/(x + i·y)`, a unit complex number.
fn unit_ratio(x: f64, y: f64) -> Complex {
    let d = x * x + y * y;
    Complex {
        re: (x * x - y * y) / d,
        im: -2.0 * x * y / d,
    }
}

/// Critical angle in radians for light inside `n_i` meeting `n_t < n_i`.
pub fn critical_angle(n_i: f64, n_t: f64) -> f64 {
    (n_t / n_i).min(1.0).asin()
}

/// Mirror direction `d` about a plane with unit normal `n`.
#[inline]
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// Refract unit direction `d` through a plane with unit normal `n` (either orientation),
/// from index `n_i` into `n_t`. `None` under total internal reflection.
#[inline]
pub fn refract(d: DVec3, n: DVec3, n_i: f64, n_t: f64) -> Option<DVec3> {
    let n = if d.dot(n) > 0.0 { -n } else { n };
    let cos_i = -d.dot(n);
    let eta = n_i / n_t;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(eta * d + (eta * cos_i - cos_t) * n)
}

#[cfg(test)]
mod tests {
    use super::*;
    const N: f64 = 2.4173;

    #[test]
    fn normal_incidence_closed_form() {
        let f = fresnel(1.0, 1.0, N);
        let r = ((N - 1.0) / (N + 1.0)).powi(2);
        assert!((f.reflectance() - r).abs() < 1e-15);
        assert!((r - 0.172).abs() < 0.001);
        // Same from inside.
        assert!((fresnel(1.0, N, 1.0).reflectance() - r).abs() < 1e-15);
    }

    #[test]
    fn energy_and_amplitude_consistency() {
        for k in 0..=100 {
            let th = (k as f64 / 100.0) * std::f64::consts::FRAC_PI_2;
            for (ni, nt) in [(1.0, N), (N, 1.0), (1.0, 1.5)] {
                let f = fresnel(th.cos(), ni, nt);
                assert!(f.r_s <= 1.0 + 1e-12 && f.r_p <= 1.0 + 1e-12);
                if !f.tir {
                    // T from amplitudes: (n_t cos_t)/(n_i cos_i)·t² must equal 1 − R.
                    if f.cos_i > 1e-9 {
                        let g = nt * f.cos_t / (ni * f.cos_i);
                        assert!((g * f.ts * f.ts - f.t_s()).abs() < 1e-12);
                        assert!((g * f.tp * f.tp - f.t_p()).abs() < 1e-12);
                    }
                } else {
                    assert!(
                        (f.rs.norm_sqr() - 1.0).abs() < 1e-12
                            && (f.rp.norm_sqr() - 1.0).abs() < 1e-12
                    );
                }
            }
        }
    }

    #[test]
    fn brewster_angle() {
        let th = N.atan();
        let f = fresnel(th.cos(), 1.0, N);
        assert!(f.r_p < 1e-20, "{}", f.r_p);
        assert!(f.r_s > 0.3);
    }

    #[test]
    fn critical_angle_diamond() {
        let m = crate::optics::Material::diamond();
        let c = critical_angle(m.ri_d(), 1.0).to_degrees();
        assert!((c - 24.4).abs() < 0.05, "{c}");
        let just_above = (c + 0.01).to_radians().cos();
        let just_below = (c - 0.01).to_radians().cos();
        assert!(fresnel(just_above, m.ri_d(), 1.0).tir);
        assert!(!fresnel(just_below, m.ri_d(), 1.0).tir);
    }

    #[test]
    fn tir_phase_difference_matches_born_and_wolf() {
        // tan(Δ/2) = cos θ sqrt(sin²θ − n²) / sin²θ with n = n_t/n_i.
        let n = 1.0 / N;
        for deg in [30.0f64, 45.0, 60.0, 80.0] {
            let th = deg.to_radians();
            let f = fresnel(th.cos(), N, 1.0);
            let expect =
                2.0 * (th.cos() * (th.sin().powi(2) - n * n).sqrt() / th.sin().powi(2)).atan();
            assert!((f.phase_difference().abs() - expect).abs() < 1e-12, "{deg}");
        }
    }

    #[test]
    fn snell_and_reflection_directions() {
        let n = DVec3::Z;
        let d = DVec3::new(0.6, 0.0, -0.8);
        let t = refract(d, n, 1.0, N).unwrap();
        assert!((t.length() - 1.0).abs() < 1e-12);
        let (si, st) = (d.x, t.x);
        assert!((si - N * st).abs() < 1e-12);
        assert_eq!(reflect(d, n), DVec3::new(0.6, 0.0, 0.8));
        assert!(refract(DVec3::new(0.6, 0.0, 0.8), n, N, 1.0).is_none());
    }
}
