//! Complex numbers and complex 3-vectors, only what the boundary conditions of a crystal
//! facet need: a wave vector with an imaginary normal component (an evanescent wave under
//! total internal reflection) and the complex fields built from it.

use glam::DVec3;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A complex number.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct C {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl C {
    /// `re + i·im`.
    #[inline]
    pub const fn new(re: f64, im: f64) -> C {
        C { re, im }
    }
    /// `x + 0i`.
    #[inline]
    pub const fn real(x: f64) -> C {
        C { re: x, im: 0.0 }
    }
    /// Complex conjugate.
    #[inline]
    pub fn conj(self) -> C {
        C::new(self.re, -self.im)
    }
    /// `|z|²`.
    #[inline]
    pub fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }
    /// `x · z` for real `x`.
    #[inline]
    pub fn scale(self, x: f64) -> C {
        C::new(self.re * x, self.im * x)
    }
}

impl Add for C {
    type Output = C;
    #[inline]
    fn add(self, o: C) -> C {
        C::new(self.re + o.re, self.im + o.im)
    }
}
impl Sub for C {
    type Output = C;
    #[inline]
    fn sub(self, o: C) -> C {
        C::new(self.re - o.re, self.im - o.im)
    }
}
impl Mul for C {
    type Output = C;
    #[inline]
    fn mul(self, o: C) -> C {
        C::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}
impl Div for C {
    type Output = C;
    #[inline]
    fn div(self, o: C) -> C {
        let d = o.norm_sqr();
        C::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
}
impl Neg for C {
    type Output = C;
    #[inline]
    fn neg(self) -> C {
        C::new(-self.re, -self.im)
    }
}

/// A complex 3-vector `re + i·im`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CVec3 {
    /// Real part.
    pub re: DVec3,
    /// Imaginary part.
    pub im: DVec3,
}

impl CVec3 {
    /// A real vector.
    #[inline]
    pub fn real(v: DVec3) -> CVec3 {
        CVec3 {
            re: v,
            im: DVec3::ZERO,
        }
    }
    /// `a + b·z` for real vectors `a`, `b` and complex `z`.
    #[inline]
    pub fn affine(a: DVec3, b: DVec3, z: C) -> CVec3 {
        CVec3 {
            re: a + b * z.re,
            im: b * z.im,
        }
    }
    /// `self · z`.
    #[inline]
    pub fn times(self, z: C) -> CVec3 {
        CVec3 {
            re: self.re * z.re - self.im * z.im,
            im: self.re * z.im + self.im * z.re,
        }
    }
    /// `self · x` for real `x`.
    #[inline]
    pub fn scale(self, x: f64) -> CVec3 {
        CVec3 {
            re: self.re * x,
            im: self.im * x,
        }
    }
    /// The bilinear product `Σ aᵢ bᵢ` (no conjugation).
    #[inline]
    pub fn dot(self, o: CVec3) -> C {
        C::new(
            self.re.dot(o.re) - self.im.dot(o.im),
            self.re.dot(o.im) + self.im.dot(o.re),
        )
    }
    /// `self · v` for a real vector `v`.
    #[inline]
    pub fn dot_real(self, v: DVec3) -> C {
        C::new(self.re.dot(v), self.im.dot(v))
    }
    /// The bilinear cross product.
    #[inline]
    pub fn cross(self, o: CVec3) -> CVec3 {
        CVec3 {
            re: self.re.cross(o.re) - self.im.cross(o.im),
            im: self.re.cross(o.im) + self.im.cross(o.re),
        }
    }
    /// `Σ |aᵢ|²`.
    #[inline]
    pub fn norm_sqr(self) -> f64 {
        self.re.length_squared() + self.im.length_squared()
    }
    /// `Re(self × conj(o))`: twice the time-averaged Poynting vector of fields `E = self`,
    /// `H = o`.
    #[inline]
    pub fn cross_conj_re(self, o: CVec3) -> DVec3 {
        // (a + ib) × (c − id) = a×c + b×d + i(b×c − a×d)
        self.re.cross(o.re) + self.im.cross(o.im)
    }
}

impl Add for CVec3 {
    type Output = CVec3;
    #[inline]
    fn add(self, o: CVec3) -> CVec3 {
        CVec3 {
            re: self.re + o.re,
            im: self.im + o.im,
        }
    }
}
impl Sub for CVec3 {
    type Output = CVec3;
    #[inline]
    fn sub(self, o: CVec3) -> CVec3 {
        CVec3 {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
}

/// Solve the complex 4×4 system `a · x = b` by Gaussian elimination with partial pivoting;
/// `None` when it is singular (a pivot of exactly zero or not finite).
pub fn solve4(mut a: [[C; 4]; 4], mut b: [C; 4]) -> Option<[C; 4]> {
    for col in 0..4 {
        let mut piv = col;
        let mut best = a[col][col].norm_sqr();
        for (r, row) in a.iter().enumerate().skip(col + 1) {
            let m = row[col].norm_sqr();
            if m > best {
                best = m;
                piv = r;
            }
        }
        if !(best > 0.0 && best.is_finite()) {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        let inv = C::real(1.0) / a[col][col];
        for r in col + 1..4 {
            let f = a[r][col] * inv;
            if f == C::default() {
                continue;
            }
            let pivot_row = a[col];
            for (x, v) in a[r].iter_mut().zip(pivot_row).skip(col) {
                *x = *x - f * v;
            }
            let v = b[col];
            b[r] = b[r] - f * v;
        }
    }
    let mut x = [C::default(); 4];
    for r in (0..4).rev() {
        let mut s = b[r];
        for (c, xc) in x.iter().enumerate().skip(r + 1) {
            s = s - a[r][c] * *xc;
        }
        x[r] = s / a[r][r];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve4_inverts_a_random_complex_system() {
        let a = [
            [
                C::new(1.0, 0.5),
                C::new(0.2, -1.0),
                C::new(0.0, 0.3),
                C::new(2.0, 0.0),
            ],
            [
                C::new(0.0, 1.0),
                C::new(1.5, 0.0),
                C::new(-0.7, 0.1),
                C::new(0.3, 0.3),
            ],
            [
                C::new(0.4, 0.0),
                C::new(0.0, 0.0),
                C::new(0.0, 0.0),
                C::new(1.0, -1.0),
            ],
            [
                C::new(0.0, 0.0),
                C::new(2.0, 2.0),
                C::new(1.0, 0.0),
                C::new(0.0, 0.5),
            ],
        ];
        let x0 = [
            C::new(1.0, 2.0),
            C::new(-0.5, 0.0),
            C::new(0.0, -3.0),
            C::new(0.25, 0.75),
        ];
        let mut b = [C::default(); 4];
        for r in 0..4 {
            for c in 0..4 {
                b[r] = b[r] + a[r][c] * x0[c];
            }
        }
        let x = solve4(a, b).unwrap();
        for (u, v) in x.iter().zip(&x0) {
            assert!((*u - *v).norm_sqr() < 1e-26, "{u:?} {v:?}");
        }
        assert!(solve4([[C::default(); 4]; 4], b).is_none());
    }
}
