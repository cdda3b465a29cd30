//! Random surfaces for the properties: a seeded generator and nets over a jittered grid with
//! a smooth random height (as the study's check14), any degrees, optionally rational.

use crate::reference::Net;

/// SplitMix64: tiny, seeded, reproducible.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }

    /// Uniform in `lo ..= hi`.
    pub fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as usize
    }

    /// A standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let a = self.range(1e-12, 1.0);
        let b = self.range(0.0, 1.0);
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

/// Clamped knots on `[0, 1]` for `count` poles of degree `p`, interior gaps uniform in
/// `[0.5, 1.5]` (normalised).
pub fn knots(rng: &mut Rng, p: usize, count: usize) -> Vec<f64> {
    let gaps: Vec<f64> = (0..=count - p - 1).map(|_| rng.range(0.5, 1.5)).collect();
    let total: f64 = gaps.iter().sum();
    let mut knots = vec![0.0; p + 1];
    let mut acc = 0.0;
    for g in &gaps[..gaps.len() - 1] {
        acc += g;
        knots.push(acc / total);
    }
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    knots
}

/// A random net: degrees `(pu, pv)`, `count = p + extra` poles per direction, a jittered
/// unit grid with a cumulative-random height, weights in `[0.5, 2]` when `rational`.
pub fn net(rng: &mut Rng, (pu, pv): (usize, usize), extra: (usize, usize), rational: bool) -> Net {
    let (nu, nv) = (pu + 1 + extra.0, pv + 1 + extra.1);
    let mut z = vec![vec![0.0; nv]; nu];
    for i in 0..nu {
        for j in 0..nv {
            let step = 0.3 * rng.normal();
            let left = if j > 0 { z[i][j - 1] } else { 0.0 };
            let up = if i > 0 { z[i - 1][j] } else { 0.0 };
            let diagonal = if i > 0 && j > 0 { z[i - 1][j - 1] } else { 0.0 };
            z[i][j] = left + up - diagonal + step;
        }
    }
    let poles = (0..nu)
        .map(|i| {
            (0..nv)
                .map(|j| {
                    [
                        i as f64 + 0.15 * rng.normal(),
                        j as f64 + 0.15 * rng.normal(),
                        0.3 * z[i][j],
                    ]
                })
                .collect()
        })
        .collect();
    let weights = rational.then(|| {
        (0..nu)
            .map(|_| (0..nv).map(|_| rng.range(0.5, 2.0)).collect())
            .collect()
    });
    Net {
        degrees: (pu, pv),
        knots_u: knots(rng, pu, nu),
        knots_v: knots(rng, pv, nv),
        poles,
        weights,
    }
}

/// A parameter in the middle 80 % of a random non-empty span of `knots` (degree `p`) whose
/// neighbourhood is interior when possible.
pub fn parameter(rng: &mut Rng, knots: &[f64], p: usize) -> f64 {
    let count = knots.len() - p - 1;
    let spans: Vec<usize> = (p..count).filter(|&j| knots[j] < knots[j + 1]).collect();
    let j = spans[rng.int(0, spans.len() - 1)];
    let (lo, hi) = (knots[j], knots[j + 1]);
    rng.range(lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo))
}
