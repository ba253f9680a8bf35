//! Seeded space-filling samples of the unit box (Latin hypercubes, Halton sets): where
//! multi-start Nelder–Mead starts.
//!
//! Both return `n` points in `[0, 1]^d`, the same for the same seed on every machine
//! (`rand`'s `StdRng`, ChaCha12, is portable).

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A Latin hypercube: each axis is cut into `n` equal strata and every stratum holds exactly one
/// point, at a random position inside it; the strata are paired at random across axes.
pub fn latin_hypercube(n: usize, d: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = StdRng::seed_from_u64(seed ^ 0x4c48_5344_4553_4947);
    let mut pts = vec![vec![0.0; d]; n];
    for j in 0..d {
        let mut perm: Vec<usize> = (0..n).collect();
        // Fisher–Yates, written out so the sequence of draws is fixed by this code.
        for i in (1..n).rev() {
            let k = rng.random_range(0..=i);
            perm.swap(i, k);
        }
        for (i, p) in pts.iter_mut().enumerate() {
            let u: f64 = rng.random();
            p[j] = (perm[i] as f64 + u) / n as f64;
        }
    }
    pts
}

const PRIMES: [u32; 16] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53];

/// The radical inverse of `i` in base `b` (van der Corput).
pub fn radical_inverse(mut i: u64, b: u32) -> f64 {
    let b = b as u64;
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= b as f64;
        r += f * (i % b) as f64;
        i /= b;
    }
    r
}

/// A Halton set (bases 2, 3, 5, …), skipping the first 20 points and shifted by a seeded random
/// offset modulo 1 (Cranley–Patterson rotation), so different seeds give different sets that
/// keep the sequence's even spread. Up to 16 dimensions; beyond that the remaining axes are
/// filled by a Latin hypercube.
pub fn halton(n: usize, d: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = StdRng::seed_from_u64(seed ^ 0x4841_4c54_4f4e_5345);
    let shift: Vec<f64> = (0..d).map(|_| rng.random()).collect();
    let extra = if d > PRIMES.len() {
        latin_hypercube(n, d - PRIMES.len(), seed)
    } else {
        Vec::new()
    };
    (0..n)
        .map(|i| {
            (0..d)
                .map(|j| {
                    if j < PRIMES.len() {
                        (radical_inverse(i as u64 + 20, PRIMES[j]) + shift[j]).fract()
                    } else {
                        extra[i][j - PRIMES.len()]
                    }
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latin_hypercube_fills_every_stratum_once() {
        let n = 7;
        let pts = latin_hypercube(n, 3, 9);
        for j in 0..3 {
            let mut strata: Vec<usize> = pts.iter().map(|p| (p[j] * n as f64) as usize).collect();
            strata.sort_unstable();
            assert_eq!(strata, (0..n).collect::<Vec<_>>());
        }
        assert_eq!(pts, latin_hypercube(n, 3, 9));
        assert_ne!(pts, latin_hypercube(n, 3, 10));
    }

    #[test]
    fn halton_is_in_the_box_and_seeded() {
        assert_eq!(radical_inverse(1, 2), 0.5);
        assert_eq!(radical_inverse(3, 2), 0.75);
        assert!((radical_inverse(5, 3) - (2.0 / 3.0 + 1.0 / 9.0)).abs() < 1e-15);
        let pts = halton(50, 4, 1);
        assert!(pts.iter().flatten().all(|&v| (0.0..1.0).contains(&v)));
        assert_eq!(pts, halton(50, 4, 1));
        assert_ne!(pts, halton(50, 4, 2));
        // Evenly spread: every half of every axis holds close to half the points.
        for j in 0..4 {
            let low = pts.iter().filter(|p| p[j] < 0.5).count();
            assert!((20..=30).contains(&low), "axis {j}: {low}");
        }
    }
}
