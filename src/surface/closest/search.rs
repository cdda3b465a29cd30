//! One query's search (the parent module's docs): the best distance and its candidates, the
//! parts' Bernstein coefficients, their resolution by convexity or halving, and the answer.

use std::collections::BinaryHeap;

use super::{
    COORDINATE_ROUNDING, Entry, MAX_DEPTH, MAX_POLISHED, MAX_RATIO_STEPS, MAX_SUBDIVISIONS, Part,
    SQUARED_NOISE, SURFACE_CLOSEST_TOLERANCE, SurfaceClosestPoint, SurfaceClosestSearch, What,
};
use crate::spline::Point;
use crate::spline::vector::{dot, sub};
use crate::surface::bernstein2::{
    Degrees, evaluate_2d, halve_2d, second_derivative_sizes, sum_of_squares,
};
use crate::surface::minimise::{certified_minimum, descend, projected_newton};

/// The state of one query's search.
pub(super) struct Search<'a, 's> {
    owner: &'a SurfaceClosestSearch<'s>,
    q: Point,
    /// Degrees `(2p, 2q)` of `N` and `D`.
    degrees: Degrees,
    rational: bool,
    /// Coefficients of `N` then `D`, `2 · degrees.len()` per block.
    arena: Vec<f64>,
    free: Vec<usize>,
    parts: Vec<Part>,
    /// The least squared distance offered so far.
    pub(super) best: f64,
    /// How far above `best` a value still counts: the tie tolerance plus the noise.
    pub(super) slack: f64,
    /// What a lower bound must reach, above the best, for its box to be dropped as a tie:
    /// `−noise` where the rounding noise is within the tie tolerance of the distance (points
    /// that close are ties), `+noise` nearer the surface, where the Bernstein values cannot
    /// tell distances apart and a box within the noise may hold a much nearer point.
    tie_margin: f64,
    /// The smallest `(u, v)` among the kept candidates.
    best_key: (f64, f64),
    /// `(u, v, squared distance, patch)` within the slack of the best when offered.
    candidates: Vec<(f64, f64, f64, usize)>,
    subdivisions: usize,
    /// Whether a part was left unresolved (depth or budget spent).
    exhausted: bool,
    /// Whether a part was dropped as below the noise of the Bernstein values.
    below_noise: bool,
    /// Room for a part's `P_μ`, `N` and `D` while it is resolved.
    scratch: Vec<f64>,
}

impl<'a, 's> Search<'a, 's> {
    pub(super) fn new(owner: &'a SurfaceClosestSearch<'s>, q: Point) -> Self {
        let (p, q_degree) = (owner.surface.u().degree(), owner.surface.v().degree());
        Search {
            owner,
            q,
            degrees: Degrees {
                m: 2 * p,
                n: 2 * q_degree,
            },
            rational: owner.surface.is_rational(),
            arena: Vec::new(),
            free: Vec::new(),
            parts: Vec::new(),
            best: f64::INFINITY,
            slack: f64::INFINITY,
            tie_margin: f64::INFINITY,
            best_key: (f64::INFINITY, f64::INFINITY),
            candidates: Vec::new(),
            subdivisions: 0,
            exhausted: false,
            below_noise: false,
            scratch: Vec::new(),
        }
    }

    /// `(slack, tie margin)` at the current best (as the curves': the tie tolerance on the
    /// distance, squared, plus the rounding allowance; see `tie_margin`).
    fn slack_at(&self) -> (f64, f64) {
        let best = self.best.sqrt();
        let scale = self.owner.size + best;
        let tolerance = SURFACE_CLOSEST_TOLERANCE * scale;
        let band = 2.0 * best * tolerance + tolerance * tolerance;
        let noise = SQUARED_NOISE * scale * scale;
        let margin = if noise <= band { -noise } else { noise };
        (band + noise, margin)
    }

    /// Records the squared distance `value` at `(u, v)` of `patch`.
    fn offer(&mut self, (u, v): (f64, f64), value: f64, patch: usize) {
        if value.is_nan() {
            return;
        }
        let value = value.max(0.0);
        if value < self.best {
            self.best = value;
            (self.slack, self.tie_margin) = self.slack_at();
            let limit = self.best + self.slack;
            self.candidates.retain(|c| c.2 <= limit);
            self.best_key = self
                .candidates
                .iter()
                .map(|c| (c.0, c.1))
                .fold((f64::INFINITY, f64::INFINITY), lexicographic_min);
        }
        if value <= self.best + self.slack {
            self.candidates.push((u, v, value, patch));
            self.best_key = lexicographic_min(self.best_key, (u, v));
        }
    }

    /// Whether a box or part with squared-distance lower bound `bound` and smallest `(u, v)`
    /// `key` can be left out: it cannot come within the slack of the best, or it cannot beat
    /// the best beyond the noise and lies after a tie already found (ties go to the smallest
    /// `(u, v)`, `u` first).
    pub(super) fn prunes(&self, bound: f64, key: (f64, f64)) -> bool {
        bound > self.best + self.slack
            || (bound >= self.best + self.tie_margin
                && lexicographic_min(key, self.best_key) == self.best_key)
    }

    /// A fresh block of the arena.
    fn allocate(&mut self) -> usize {
        match self.free.pop() {
            Some(block) => block,
            None => {
                let block = self.arena.len() / (2 * self.degrees.len());
                self.arena
                    .resize(self.arena.len() + 2 * self.degrees.len(), 0.0);
                block
            }
        }
    }

    /// `(N, D)` of a block.
    fn block(&self, block: usize) -> (&[f64], &[f64]) {
        let len = self.degrees.len();
        let start = 2 * len * block;
        (
            &self.arena[start..start + len],
            &self.arena[start + len..start + 2 * len],
        )
    }

    /// The parameters of a part's local point `(σ, τ)`.
    fn parameters(&self, part: &Part, (sigma, tau): (f64, f64)) -> (f64, f64) {
        let patch = &self.owner.patches[part.patch];
        let s = part.s.0 + sigma * (part.s.1 - part.s.0);
        let t = part.t.0 + tau * (part.t.1 - part.t.0);
        let (u0, u1) = patch.rect.u;
        let (v0, v1) = patch.rect.v;
        (
            (u0 + s * (u1 - u0)).min(patch.ends.0),
            (v0 + t * (v1 - v0)).min(patch.ends.1),
        )
    }

    /// The squared distance at a part's local point `(σ, τ)` from its coefficients.
    fn value_at(&self, block: usize, (sigma, tau): (f64, f64)) -> f64 {
        let (n, d) = self.block(block);
        let value = evaluate_2d(n, self.degrees, sigma, tau).0;
        if self.rational {
            value / evaluate_2d(d, self.degrees, sigma, tau).0
        } else {
            value
        }
    }

    /// The least ratio of a block's coefficients: a lower bound of `N / D` on its part.
    fn lower_bound(&self, block: usize) -> f64 {
        let (n, d) = self.block(block);
        if self.rational {
            n.iter()
                .zip(d)
                .map(|(a, b)| a / b)
                .fold(f64::INFINITY, f64::min)
        } else {
            n.iter().copied().fold(f64::INFINITY, f64::min)
        }
    }

    /// Offers the corners `corners` (local `(σ, τ)` in `{0, 1}²`) of `part`: a Bézier net's
    /// corner coefficients are values of the surface's squared distance.
    fn offer_corners(&mut self, part: &Part, corners: &[(usize, usize)]) {
        let Degrees { m, n } = self.degrees;
        for &(i, j) in corners {
            let (values, weights) = self.block(part.block);
            let k = (i * m) * (n + 1) + j * n;
            let value = if self.rational {
                values[k] / weights[k]
            } else {
                values[k]
            };
            let at = self.parameters(part, (i as f64, j as f64));
            self.offer(at, value, part.patch);
        }
    }

    /// The first part of patch `patch`: its coefficients, its corners offered; the heap entry.
    pub(super) fn start_patch(&mut self, patch: usize) -> Option<Entry> {
        let surface = self.owner.surface;
        let (p, q) = (surface.u().degree(), surface.v().degree());
        let size = (p + 1) * (q + 1);
        let net = &self.owner.nets[patch * size..(patch + 1) * size];
        // (p + 1)(q + 1) <= 16² points: the degrees are at most MAX_DEGREE.
        const ROOM: usize = (crate::spline::MAX_DEGREE + 1) * (crate::spline::MAX_DEGREE + 1);
        let mut factors = [[0.0; ROOM]; 3];
        let mut weights = [0.0; ROOM];
        for (k, h) in net.iter().enumerate() {
            for c in 0..3 {
                factors[c][k] = h[c] - self.q[c] * h[3];
            }
            weights[k] = h[3];
        }
        let block = self.allocate();
        let len = self.degrees.len();
        let start = 2 * len * block;
        let degrees = Degrees { m: p, n: q };
        {
            let (n, d) = self.arena[start..start + 2 * len].split_at_mut(len);
            sum_of_squares(
                &[
                    &factors[0][..size],
                    &factors[1][..size],
                    &factors[2][..size],
                ],
                degrees,
                n,
            );
            if self.rational {
                sum_of_squares(&[&weights[..size]], degrees, d);
            } else {
                d.iter_mut().for_each(|x| *x = 1.0);
            }
        }
        let part = Part {
            patch,
            block,
            s: (0.0, 1.0),
            t: (0.0, 1.0),
            depth: (0, 0),
        };
        self.offer_corners(&part, &[(0, 0), (1, 0), (0, 1), (1, 1)]);
        Some(self.entry(part))
    }

    /// Registers `part` and returns its heap entry.
    fn entry(&mut self, part: Part) -> Entry {
        let bound = self.lower_bound(part.block);
        let key = self.parameters(&part, (0.0, 0.0));
        self.parts.push(part);
        Entry {
            bound,
            key,
            what: What::Part(self.parts.len() - 1),
        }
    }

    /// Resolves part `index` by convexity, or halves it (module docs).
    pub(super) fn process(&mut self, index: usize, heap: &mut BinaryHeap<Entry>) {
        let part = self.parts[index];
        if self.within_noise(&part) {
            // Every value of the part is within the Bernstein values' noise of the best:
            // halving cannot tell its points apart. Its centre is offered, and the answer is
            // polished with the exact partials (`finish`).
            let centre = self.value_at(part.block, (0.5, 0.5));
            let at = self.parameters(&part, (0.5, 0.5));
            self.offer(at, centre, part.patch);
            self.below_noise = true;
            self.free.push(part.block);
            return;
        }
        if self.resolves(&part) {
            self.free.push(part.block);
            return;
        }
        // Halve where the lower bound's gap is larger: the larger second derivative (in the
        // part's own parameters).
        let [spread_s, spread_t] = {
            let (n, _) = self.block(part.block);
            second_derivative_sizes(n, self.degrees)
        };
        let spread = |k: usize| [spread_s, spread_t][k];
        let in_s = match (part.depth.0 >= MAX_DEPTH, part.depth.1 >= MAX_DEPTH) {
            (true, true) => {
                self.exhausted = true;
                self.free.push(part.block);
                return;
            }
            (true, false) => false,
            (false, true) => true,
            (false, false) if spread(0) == spread(1) => part.depth.0 <= part.depth.1,
            (false, false) => spread(0) > spread(1),
        };
        if self.subdivisions >= MAX_SUBDIVISIONS {
            self.exhausted = true;
            let centre = self.value_at(part.block, (0.5, 0.5));
            let at = self.parameters(&part, (0.5, 0.5));
            self.offer(at, centre, part.patch);
            self.free.push(part.block);
            return;
        }
        self.subdivisions += 1;
        let (left_block, right_block) = (self.allocate(), self.allocate());
        let len = self.degrees.len();
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.resize(3 * len, 0.0);
        for offset in [0, len] {
            let (source, halves) = scratch.split_at_mut(len);
            let (left, right) = halves.split_at_mut(len);
            source.copy_from_slice(&self.arena[2 * len * part.block + offset..][..len]);
            halve_2d(source, self.degrees, in_s, left, right);
            self.arena[2 * len * left_block + offset..][..len].copy_from_slice(left);
            self.arena[2 * len * right_block + offset..][..len].copy_from_slice(right);
        }
        self.scratch = scratch;
        self.free.push(part.block);
        let (mut left, mut right) = (part, part);
        left.block = left_block;
        right.block = right_block;
        if in_s {
            let middle = 0.5 * (part.s.0 + part.s.1);
            (left.s.1, right.s.0) = (middle, middle);
            left.depth.0 += 1;
            right.depth.0 += 1;
            self.offer_corners(&left, &[(1, 0), (1, 1)]);
        } else {
            let middle = 0.5 * (part.t.0 + part.t.1);
            (left.t.1, right.t.0) = (middle, middle);
            left.depth.1 += 1;
            right.depth.1 += 1;
            self.offer_corners(&left, &[(0, 1), (1, 1)]);
        }
        for child in [left, right] {
            let entry = self.entry(child);
            heap.push(entry);
        }
    }

    /// Whether every coefficient ratio of `part` lies within the noise of the best (the
    /// squared distance's rounding, `SQUARED_NOISE (size + √best)²`).
    fn within_noise(&self, part: &Part) -> bool {
        let (n, d) = self.block(part.block);
        let scale = self.owner.size + self.best.sqrt();
        let limit = self.best + SQUARED_NOISE * scale * scale;
        if self.rational {
            n.iter().zip(d).all(|(a, b)| a / b <= limit)
        } else {
            n.iter().all(|&a| a <= limit)
        }
    }

    /// Whether `part` is resolved by a certified minimum of `P_μ = N − μ D`
    /// ([`certified_minimum`]: convexity, or monotony towards an edge), with Dinkelbach's
    /// steps on `μ` (module docs); the minima found are offered.
    fn resolves(&mut self, part: &Part) -> bool {
        let len = self.degrees.len();
        let start = 2 * len * part.block;
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.resize(3 * len, 0.0);
        let (polynomial, rest) = scratch.split_at_mut(len);
        let (n, d) = rest.split_at_mut(len);
        n.copy_from_slice(&self.arena[start..start + len]);
        d.copy_from_slice(&self.arena[start + len..start + 2 * len]);
        let resolved = self.resolves_with(part, polynomial, n, d);
        self.scratch = scratch;
        resolved
    }

    /// [`Search::resolves`] with the part's `N`, `D` and room for `P_μ`.
    fn resolves_with(&mut self, part: &Part, polynomial: &mut [f64], n: &[f64], d: &[f64]) -> bool {
        let largest_weight = d.iter().copied().fold(0.0, f64::max);
        let noise_at = |best: f64, size: f64| {
            let scale = size + best.max(0.0).sqrt();
            SQUARED_NOISE * scale * scale * largest_weight
        };
        if !self.rational {
            // D = 1: P_μ = N − μ has the minimum of N wherever μ is; one certificate of N's.
            let Some(minimum) = certified_minimum(n, self.degrees) else {
                self.offer_descent(part, n);
                return false;
            };
            let x = (minimum.point[0], minimum.point[1]);
            let at = self.parameters(part, x);
            self.offer(at, minimum.value, part.patch);
            return minimum.bound - self.best >= -noise_at(self.best, self.owner.size);
        }
        let mut mu = if self.best.is_finite() {
            self.best
        } else {
            self.value_at(part.block, (0.5, 0.5))
        };
        for _ in 0..MAX_RATIO_STEPS {
            for ((p, &a), &b) in polynomial.iter_mut().zip(n).zip(d) {
                *p = a - mu * b;
            }
            let Some(minimum) = certified_minimum(polynomial, self.degrees) else {
                self.offer_descent(part, polynomial);
                return false;
            };
            let x = (minimum.point[0], minimum.point[1]);
            let ratio = self.value_at(part.block, x);
            let at = self.parameters(part, x);
            self.offer(at, ratio, part.patch);
            if minimum.bound >= -noise_at(mu, self.owner.size) {
                return true;
            }
            if ratio < mu {
                mu = ratio;
            } else {
                return false;
            }
        }
        false
    }

    /// With no certificate: offers where a descent on `polynomial` from its least coefficient
    /// leads, so that the best distance (and what it prunes) improves.
    fn offer_descent(&mut self, part: &Part, polynomial: &[f64]) {
        let (x, _, _) = descend(polynomial, self.degrees);
        let ratio = self.value_at(part.block, (x[0], x[1]));
        let at = self.parameters(part, (x[0], x[1]));
        self.offer(at, ratio, part.patch);
    }

    /// The answer (module docs of the parent): candidates measured with the surface
    /// evaluator and polished, the smallest `(u, v)` among those within the tolerance of the
    /// least distance.
    pub(super) fn finish(self) -> SurfaceClosestPoint {
        if std::env::var_os("SURFACE_STATS").is_some() {
            eprintln!(
                "STATS parts {} subdivisions {} candidates {} below_noise {} exhausted {}",
                self.parts.len(),
                self.subdivisions,
                self.candidates.len(),
                self.below_noise,
                self.exhausted
            );
        }
        let surface = self.owner.surface;
        let limit = self.best + self.slack;
        let measure = |u: f64, v: f64, patch: usize| {
            let (a, b) = self.owner.patches[patch].rect.spans;
            let point = surface.partials_in_spans(a, b, u, v, 0).point();
            (
                u,
                v,
                point,
                crate::spline::vector::distance(point, self.q),
                patch,
            )
        };
        let mut measured: Vec<_> = self
            .candidates
            .iter()
            .filter(|c| c.2 <= limit)
            .map(|&(u, v, _, patch)| measure(u, v, patch))
            .collect();
        if measured.is_empty() {
            let [(u0, _), (v0, _)] = self.owner.range;
            let point = surface.point(u0, v0);
            let d = crate::spline::vector::distance(point, self.q);
            return SurfaceClosestPoint {
                u: u0,
                v: v0,
                point,
                distance: d,
            };
        }
        measured.sort_by(|a, b| {
            a.3.total_cmp(&b.3)
                .then(a.0.total_cmp(&b.0))
                .then(a.1.total_cmp(&b.1))
        });
        measured.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
        let nearest = measured[0].3;
        let near_surface = nearest * nearest <= SQUARED_NOISE * (self.owner.size + nearest).powi(2);
        let polished = if near_surface || self.exhausted || self.below_noise {
            MAX_POLISHED
        } else {
            1
        };
        let starts: Vec<_> = measured.iter().take(polished).copied().collect();
        for (u, v, _, d, patch) in starts {
            let (pu, pv) = self.polish(u, v, patch);
            let found = measure(pu, pv, patch);
            if found.3 < d {
                measured.push(found);
            }
        }
        // Ties go to the smallest (u, v): also try the best point moved onto the lower edges
        // of its patch and of the range (the minima found there may lie a rounding error
        // inside them).
        let (bu, bv, _, _, patch) = *measured
            .iter()
            .min_by(|a, b| a.3.total_cmp(&b.3))
            .unwrap_or(&measured[0]);
        let rect = self.owner.patches[patch].rect;
        let [(range_u, _), (range_v, _)] = self.owner.range;
        for (u, v) in [(rect.u.0, bv), (bu, rect.v.0), (rect.u.0, rect.v.0)] {
            if (u, v) != (bu, bv) {
                measured.push(measure(u, v, patch));
            }
        }
        if range_u == rect.u.0 || range_v == rect.v.0 {
            measured.push(measure(range_u.max(rect.u.0), range_v.max(rect.v.0), patch));
        }
        let least = measured.iter().map(|c| c.3).fold(f64::INFINITY, f64::min);
        let tie = least
            + SURFACE_CLOSEST_TOLERANCE * (self.owner.size + least)
            + COORDINATE_ROUNDING * self.owner.magnitude;
        let (u, v, point, distance, _) = measured
            .into_iter()
            .filter(|c| c.3 <= tie)
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)))
            .unwrap_or((f64::NAN, f64::NAN, self.q, 0.0, 0));
        SurfaceClosestPoint {
            u,
            v,
            point,
            distance,
        }
    }

    /// The local minimum of `|S(u, v) − q|²` near `(u, v)` in the rectangle of `patch`:
    /// projected Newton steps with the exact partials (`∇g = 2 (S − q) · (S_u, S_v)`, the
    /// Hessian `2 (S_a · S_b + (S − q) · S_ab)`), halved while they do not descend.
    fn polish(&self, u: f64, v: f64, patch: usize) -> (f64, f64) {
        let surface = self.owner.surface;
        let rect = &self.owner.patches[patch];
        let (a, b) = rect.rect.spans;
        let lower = [rect.rect.u.0, rect.rect.v.0];
        let upper = [rect.ends.0, rect.ends.1];
        let evaluate = |x: [f64; 2]| {
            let partials = surface.partials_in_spans(a, b, x[0], x[1], 2);
            let gap = sub(partials.point(), self.q);
            let [su, sv] = [partials.du(), partials.dv()];
            let (suu, suv, svv) = (
                partials.values[2][0],
                partials.values[1][1],
                partials.values[0][2],
            );
            let gradient = [dot(gap, su), dot(gap, sv)];
            let hessian = [
                dot(su, su) + dot(gap, suu),
                dot(su, sv) + dot(gap, suv),
                dot(sv, sv) + dot(gap, svv),
            ];
            (dot(gap, gap), gradient, hessian)
        };
        let (x, _, _) = projected_newton([u, v], lower, upper, evaluate);
        (x[0], x[1])
    }
}

/// The lexicographically smaller of two `(u, v)`.
fn lexicographic_min(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    if b.0 < a.0 || (b.0 == a.0 && b.1 < a.1) {
        b
    } else {
        a
    }
}
