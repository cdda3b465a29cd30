//! The closest point of a curve to a query point: the global minimum of the distance over a
//! parameter range, with the range's ends and the curve's corners included.
//!
//! The range is cut into Bézier pieces, one per knot span (blossoming). On a piece with
//! homogeneous Bézier points `(X_i, W_i)` and local parameter `s ∈ [0, 1]`, the squared
//! distance to `q` is `g(s) = N(s) / D(s)` with
//!
//! * `N = |X(s) - q W(s)|²` (degree `2p`) and `D = W(s)²` (`D = 1` for polynomial curves),
//!   both in Bernstein form;
//! * since every coefficient of `D` is positive (positive weights), `g >= min_k N_k / D_k` on
//!   the piece: a lower bound (the convex hull property of the graph of `g`), which tightens
//!   with the square of the width as a piece is halved;
//! * `g'` has the sign of `M = N' D - N D'` (`M = N'` when `D = 1`), also in Bernstein form.
//!
//! The pieces' bounding boxes (of their projected Bézier points) form a hierarchy
//! ([`super::box_tree`], shared with the surfaces' search): a balanced binary tree whose nodes
//! hold pieces near each other in space and the box of them all. The search
//! walks it depth first, the nearer child first, and drops every node whose box cannot come
//! within the tolerance of the best distance found: on a curve of many pieces a query visits
//! a few dozen nodes, not every piece. At each piece reached it takes the distance at the
//! piece's ends (range ends and corners among them: a corner is a piece end), then searches
//! it depth first: a part is dropped when its lower bound cannot come within the tolerance of
//! the best distance found; a part where `M`'s coefficients change sign once, from negative
//! to positive, holds exactly one interior minimum, found by Newton's method safeguarded by
//! bisection on `M`; a part where `M` has one sign has its minimum at an end; any other part
//! is halved (de Casteljau). The candidates are then measured again with the curve evaluator
//! and the nearest polished by Newton's method on the exact derivatives (the Bernstein values
//! cannot tell apart distances within their rounding noise, about `1e-7` of the size), and the
//! smallest parameter among those within [`CLOSEST_POINT_TOLERANCE`] of the least distance is
//! the answer. Work per query is bounded ([`MAX_HALVINGS`] halvings, [`MAX_POLISHED`]
//! polishes), whatever the input.
//!
//! One file for one algorithm: the search and the Bernstein forms it bounds, halves and
//! solves are read together (about 850 lines with the hierarchy and the polish); the rest is
//! its unit tests.

use super::MAX_DEGREE;
use super::basis::find_span;
use super::bernstein::{BINOMIAL, MAX_RATIO_DEGREE, convolve, halve, unscale, value_and_slope};
use super::box_tree::{self, BoxItem, BoxNode, NodeContent};
use super::curve::Curve;
use super::vector::{Point, distance};
use smallvec::SmallVec;

/// Ties and precision: among parameters whose distances lie within
/// `CLOSEST_POINT_TOLERANCE · (size + d)` of the least distance `d` (`size`: the diagonal of the
/// control points' bounding box), the smallest is returned.
pub const CLOSEST_POINT_TOLERANCE: f64 = 1e-12;

/// Rounding allowance of the Bernstein values of the squared distance, relative to
/// `(size + d)²`: the search keeps parts that may lie this close to the best value, so that
/// noise never prunes the true minimum (the candidates are measured again exactly).
const SQUARED_NOISE: f64 = 64.0 * f64::EPSILON;

/// Halvings of one piece at most: its parts are then `2^-52` of it.
const MAX_DEPTH: u32 = 52;

/// Halvings per query at most, which bounds the time whatever the input.
pub const MAX_HALVINGS: usize = 4096;

/// Newton's method stops when a step moves the local parameter by at most this (the part's
/// width times `1e-14`: far below the tie tolerance, and above the rounding noise of the step).
const ROOT_STEP_TOLERANCE: f64 = 1e-14;

/// Iterations of the safeguarded Newton method at most (bisection alone needs about 60).
const MAX_ROOT_ITERATIONS: usize = 100;

/// Why a closest-point search cannot run.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum ClosestPointError {
    /// An end of the range is not a finite number.
    #[error("range end {index} is not a finite number")]
    NonFiniteRange { index: usize },
    /// An end of the range lies outside the curve's domain.
    #[error("range end {value} lies outside the domain [{}, {}]", domain.0, domain.1)]
    RangeOutsideDomain {
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
    /// The range's lower end is above its upper end.
    #[error("the range [{lo}, {hi}] is reversed: its first value must not exceed its second")]
    ReversedRange { lo: f64, hi: f64 },
}

impl ClosestPointError {
    /// Which end of the range (0 or 1) is at fault.
    pub fn range_index(&self) -> usize {
        match *self {
            ClosestPointError::NonFiniteRange { index }
            | ClosestPointError::RangeOutsideDomain { index, .. } => index,
            ClosestPointError::ReversedRange { .. } => 0,
        }
    }
}

impl Curve {
    /// `range` (default: the whole domain) checked against the domain, each end just outside
    /// it taken as the domain's end ([`Curve::snap_to_domain`]); shared by the closest-point
    /// search and the arc length.
    pub(crate) fn checked_range(
        &self,
        range: Option<(f64, f64)>,
    ) -> Result<(f64, f64), ClosestPointError> {
        let domain = self.domain();
        let (lo, hi) = range.unwrap_or(domain);
        let mut ends = [lo, hi];
        for (index, value) in ends.iter_mut().enumerate() {
            if !value.is_finite() {
                return Err(ClosestPointError::NonFiniteRange { index });
            }
            *value = self
                .snap_to_domain(*value)
                .ok_or(ClosestPointError::RangeOutsideDomain {
                    index,
                    value: *value,
                    domain,
                })?;
        }
        let [lo, hi] = ends;
        if lo > hi {
            return Err(ClosestPointError::ReversedRange { lo, hi });
        }
        Ok((lo, hi))
    }
}

/// The closest point found for one query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestPoint {
    /// The parameter `u` of the closest point.
    pub parameter: f64,
    /// The curve point `s(u)`.
    pub point: Point,
    /// `|s(u) - q|`.
    pub distance: f64,
}

/// A curve's range cut into Bézier pieces, ready for many queries.
#[derive(Debug, Clone)]
pub struct ClosestPointSearch<'c> {
    curve: &'c Curve,
    range: (f64, f64),
    /// Homogeneous Bézier points, `p + 1` per piece.
    points: Vec<[f64; 4]>,
    pieces: Vec<PieceBox>,
    /// The bounding-box hierarchy over the pieces ([`box_tree::build`]); `nodes[0]` is the
    /// root (none when the range is a single parameter).
    nodes: Vec<BoxNode<f64>>,
    size: f64,
    /// `s(hi)` when the curve jumps at `hi` (it then differs from the last piece's end).
    end_point: Option<Point>,
}

/// A piece's parameter interval and the bounding box of its projected Bézier points (which
/// holds the piece: positive weights keep the convex hull property).
#[derive(Debug, Clone, Copy)]
struct PieceBox {
    lo: f64,
    hi: f64,
    /// The knot span `m` whose polynomial the piece is.
    span: usize,
    /// The parameter that stands for the piece's end: `hi`, or the float just below it when
    /// the curve jumps there (an interior knot of multiplicity `p + 1`), where the piece's end
    /// is the limit from the left and `s(hi)` the next piece's start.
    end_parameter: f64,
    min: Point,
    max: Point,
}

impl<'c> ClosestPointSearch<'c> {
    /// Cuts `range` (default: the whole domain) of `curve` into Bézier pieces. An end of the
    /// range just outside the domain is taken as the domain's end ([`Curve::snap_to_domain`]).
    pub fn new(curve: &'c Curve, range: Option<(f64, f64)>) -> Result<Self, ClosestPointError> {
        let domain = curve.domain();
        let (lo, hi) = curve.checked_range(range)?;
        let p = curve.degree();
        let knots = curve.knots();
        let mut points = Vec::new();
        let mut pieces = Vec::new();
        let mut start = lo;
        let mut out = [[0.0; 4]; MAX_DEGREE + 1];
        while start < hi {
            let span = find_span(knots, p, start);
            let end = knots[span + 1].min(hi);
            if end <= start {
                break;
            }
            curve.bezier_piece_in_span(knots, span, start, end, &mut out);
            let mut min = [f64::INFINITY; 3];
            let mut max = [f64::NEG_INFINITY; 3];
            for point in &out[..=p] {
                let projected = project(point);
                for c in 0..3 {
                    min[c] = min[c].min(projected[c]);
                    max[c] = max[c].max(projected[c]);
                }
            }
            points.extend_from_slice(&out[..=p]);
            let jumps = end < domain.1 && knots.iter().filter(|&&u| u == end).count() > p;
            pieces.push(PieceBox {
                lo: start,
                hi: end,
                span,
                end_parameter: if jumps { float_below(end) } else { end },
                min,
                max,
            });
            start = end;
        }
        let size = bounding_box_diagonal(curve.control_points());
        // When the range ends where the curve jumps, `s(hi)` starts no piece of the range.
        let jump_at_end = pieces
            .last()
            .filter(|last| last.end_parameter != last.hi)
            .is_some();
        let items: Vec<BoxItem<f64>> = pieces
            .iter()
            .map(|piece| BoxItem {
                min: piece.min,
                max: piece.max,
                key: piece.lo,
            })
            .collect();
        let nodes = box_tree::build(&items);
        Ok(ClosestPointSearch {
            curve,
            range: (lo, hi),
            points,
            pieces,
            nodes,
            size,
            end_point: jump_at_end.then(|| curve.point_unchecked(hi)),
        })
    }

    /// The range searched.
    pub fn range(&self) -> (f64, f64) {
        self.range
    }

    /// The closest point of the range to `q` (`z = 0` for a planar curve): the global minimum
    /// of `|s(u) - q|` (module docs), the smallest parameter among ties within
    /// [`CLOSEST_POINT_TOLERANCE`].
    pub fn closest(&self, q: Point) -> ClosestPoint {
        let p = self.curve.degree();
        let rational = self.curve.is_rational();
        let mut search = Search::new(self.size);
        let coordinates = self.curve.dimension().count();
        let Some(root) = self.nodes.first() else {
            // An empty range `lo == hi`: its one point.
            let point = self.curve.point_unchecked(self.range.0);
            return ClosestPoint {
                parameter: self.range.0,
                point,
                distance: distance(point, q),
            };
        };
        if let Some(end_point) = self.end_point {
            search.offer(self.range.1, squared_distance(q, end_point));
        }
        // Depth first through the hierarchy, the nearer half first: the first pieces searched
        // most likely hold the answer, and the distance found there prunes most boxes high up.
        // A piece's two end points are offered when it is reached (the range's ends, the
        // corners and both sides of a jump are piece ends); a pruned box cannot hold a point
        // within the slack of the best.
        let mut stack: SmallVec<[(usize, f64); 64]> = SmallVec::new();
        stack.push((0, root.squared_distance(q, coordinates)));
        while let Some((index, bound)) = stack.pop() {
            let node = &self.nodes[index];
            if search.prunes(bound, node.from) {
                continue;
            }
            let leaf = match node.content {
                NodeContent::Halves(left, right) => {
                    let left_bound = self.nodes[left].squared_distance(q, coordinates);
                    let right_bound = self.nodes[right].squared_distance(q, coordinates);
                    if left_bound <= right_bound {
                        stack.push((right, right_bound));
                        stack.push((left, left_bound));
                    } else {
                        stack.push((left, left_bound));
                        stack.push((right, right_bound));
                    }
                    continue;
                }
                NodeContent::Item(leaf) => leaf,
            };
            let piece = &self.pieces[leaf];
            let bezier = &self.points[leaf * (p + 1)..(leaf + 1) * (p + 1)];
            search.offer(piece.lo, squared_distance(q, project(&bezier[0])));
            search.offer(
                piece.end_parameter,
                squared_distance(q, project(&bezier[p])),
            );
            match (p, rational) {
                (3, false) => search.piece::<7>(bezier, q, 3, false, coordinates, piece),
                (3, true) => search.piece::<13>(bezier, q, 3, true, coordinates, piece),
                _ => search.piece::<{ MAX_RATIO_DEGREE + 1 }>(
                    bezier,
                    q,
                    p,
                    rational,
                    coordinates,
                    piece,
                ),
            }
        }
        search.finish(self.curve, q, self.range.0, &self.pieces)
    }
}

/// The largest float below `x` (finite `x`).
fn float_below(x: f64) -> f64 {
    if x == 0.0 {
        -f64::from_bits(1)
    } else if x > 0.0 {
        f64::from_bits(x.to_bits() - 1)
    } else {
        f64::from_bits(x.to_bits() + 1)
    }
}

/// The Euclidean point of a homogeneous one.
fn project(point: &[f64; 4]) -> Point {
    [
        point[0] / point[3],
        point[1] / point[3],
        point[2] / point[3],
    ]
}

fn squared_distance(a: Point, b: Point) -> f64 {
    (0..3).map(|c| (a[c] - b[c]) * (a[c] - b[c])).sum()
}

/// The diagonal of the points' bounding box.
fn bounding_box_diagonal(points: &[Point]) -> f64 {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for point in points {
        for c in 0..3 {
            min[c] = min[c].min(point[c]);
            max[c] = max[c].max(point[c]);
        }
    }
    distance(min, max)
}

/// A part `[s0, s1]` of a piece: Bernstein coefficients (the first of `LEN` slots) of `N`,
/// `D` (rational only) and `M` on it.
#[derive(Clone, Copy)]
struct Part<const LEN: usize> {
    numerator: [f64; LEN],
    denominator: [f64; LEN],
    slope: [f64; LEN],
    s0: f64,
    s1: f64,
    depth: u32,
}

/// The state of one query's search.
struct Search {
    size: f64,
    /// The least squared distance offered so far.
    best: f64,
    /// [`Search::slack`] at the current `best` (recomputed when `best` falls).
    slack: f64,
    /// The rounding allowance alone, `SQUARED_NOISE (size + √best)²`.
    noise: f64,
    /// The smallest parameter among the kept candidates.
    best_parameter: f64,
    /// Parameters whose squared distance lay within the slack of the best when offered.
    candidates: SmallVec<[(f64, f64); 8]>,
    halvings: usize,
    /// Whether a part was left unresolved (depth or halving budget spent).
    exhausted: bool,
}

impl Search {
    fn new(size: f64) -> Self {
        Search {
            size,
            best: f64::INFINITY,
            slack: f64::INFINITY,
            noise: f64::INFINITY,
            best_parameter: f64::INFINITY,
            candidates: SmallVec::new(),
            halvings: 0,
            exhausted: false,
        }
    }

    /// How far above the best squared distance a value still counts: the tie tolerance on
    /// the distance, plus the rounding allowance (kept in `slack`).
    fn slack_at(&self) -> (f64, f64) {
        let best = self.best.sqrt();
        let tolerance = CLOSEST_POINT_TOLERANCE * (self.size + best);
        let scale = self.size + best;
        let noise = SQUARED_NOISE * scale * scale;
        (
            2.0 * best * tolerance + tolerance * tolerance + noise,
            noise,
        )
    }

    /// Records the squared distance `value` at parameter `u`.
    fn offer(&mut self, u: f64, value: f64) {
        if value.is_nan() {
            return;
        }
        // Rounding can make a squared distance near zero slightly negative.
        let value = value.max(0.0);
        if value < self.best {
            self.best = value;
            (self.slack, self.noise) = self.slack_at();
            let limit = self.best + self.slack;
            self.candidates.retain(|&mut (_, v)| v <= limit);
            self.best_parameter = self
                .candidates
                .iter()
                .fold(f64::INFINITY, |m, &(u, _)| m.min(u));
        }
        if value <= self.best + self.slack {
            self.candidates.push((u, value));
            self.best_parameter = self.best_parameter.min(u);
        }
    }

    /// Whether a part starting at parameter `from` with squared-distance lower bound `bound`
    /// can be left out: it cannot come within the slack of the best, or it cannot beat the
    /// best even allowing for the rounding noise of the bound and lies right of a tie already
    /// found (ties go to the smallest parameter). Near the curve, where every part close to
    /// the query is within the noise of the best, nothing is pruned as a tie: such a part may
    /// hold a point much nearer than the best found so far.
    fn prunes(&self, bound: f64, from: f64) -> bool {
        bound > self.best + self.slack
            || (bound >= self.best + self.noise && from >= self.best_parameter)
    }

    /// Searches one piece (module docs); `bezier` holds its `p + 1` homogeneous points.
    #[inline(always)]
    fn piece<const LEN: usize>(
        &mut self,
        bezier: &[[f64; 4]],
        q: Point,
        p: usize,
        rational: bool,
        coordinates: usize,
        piece: &PieceBox,
    ) {
        let len = 2 * p + 1;
        let slope_len = if rational { 4 * p } else { 2 * p };
        let mut part = Part::<LEN> {
            numerator: [0.0; LEN],
            denominator: [0.0; LEN],
            slope: [0.0; LEN],
            s0: 0.0,
            s1: 1.0,
            depth: 0,
        };
        squared_distance_coefficients(bezier, q, p, rational, coordinates, &mut part);
        let parameter = |s: f64| (piece.lo + s * (piece.hi - piece.lo)).min(piece.end_parameter);
        let value = |part: &Part<LEN>, index: usize| {
            if rational {
                part.numerator[index] / part.denominator[index]
            } else {
                part.numerator[index]
            }
        };
        // Depth first: the stack holds at most one part per level (and rarely more than a few).
        let mut stack: SmallVec<[Part<LEN>; 8]> = SmallVec::new();
        stack.push(part);
        while let Some(part) = stack.pop() {
            let bound = (0..len)
                .map(|k| value(&part, k))
                .fold(f64::INFINITY, f64::min);
            if self.prunes(bound, parameter(part.s0)) {
                continue;
            }
            let slope = &part.slope[..slope_len];
            let first_sign = slope.iter().copied().find(|&m| m != 0.0).unwrap_or(0.0);
            if !slope.iter().any(|&m| m < 0.0) || !slope.iter().any(|&m| m > 0.0) {
                // Monotone: the minimum is at an end, offered already.
                continue;
            }
            if first_sign < 0.0 && sign_changes(slope) == 1 {
                // One interior minimum: where M crosses zero upwards.
                let root = upward_root(slope);
                let (n, _) = value_and_slope(&part.numerator[..len], root);
                let squared = if rational {
                    n / value_and_slope(&part.denominator[..len], root).0
                } else {
                    n
                };
                let s = part.s0 + root * (part.s1 - part.s0);
                self.offer(parameter(s), squared);
                continue;
            }
            if part.depth >= MAX_DEPTH || self.halvings >= MAX_HALVINGS {
                self.exhausted = true;
                continue;
            }
            self.halvings += 1;
            let (mut left, mut right) = (part, part);
            let middle = 0.5 * (part.s0 + part.s1);
            left.s1 = middle;
            right.s0 = middle;
            left.depth += 1;
            right.depth += 1;
            halve(
                &part.numerator[..len],
                &mut left.numerator[..len],
                &mut right.numerator[..len],
            );
            if rational {
                halve(
                    &part.denominator[..len],
                    &mut left.denominator[..len],
                    &mut right.denominator[..len],
                );
            }
            halve(
                &part.slope[..slope_len],
                &mut left.slope[..slope_len],
                &mut right.slope[..slope_len],
            );
            self.offer(parameter(middle), value(&left, len - 1));
            stack.push(right);
            stack.push(left);
        }
    }

    /// The answer: the candidates measured with the curve evaluator and polished (below), the
    /// smallest parameter among those within the tolerance of the least distance.
    ///
    /// Polishing: the Bernstein values are only good to their rounding noise,
    /// `√SQUARED_NOISE` (about `1.2e-7`) of the size in distance near the curve, so a query
    /// that close may have many candidates that tie within the noise (a closed curve's seam
    /// offers both ends). When the least distance is that small, or a part was left
    /// unresolved, a safeguarded Newton iteration on `g(u) = (s(u) - q) · s'(u)` with exact
    /// derivatives, from each of the [`MAX_POLISHED`] nearest candidates (measured) within
    /// their pieces, finds the nearest point there to the evaluator's precision. (Elsewhere
    /// the search's own roots are that precise already, and polishing every query would
    /// triple its cost: 46 k instructions instead of 12 k on the benchmark cubic, measured.)
    fn finish(&self, curve: &Curve, q: Point, fallback: f64, pieces: &[PieceBox]) -> ClosestPoint {
        let limit = self.best + self.slack;
        let measure = |u: f64, span: Option<usize>| {
            let point = match span {
                Some(span) => {
                    let mut value = [[0.0; 3]; 1];
                    curve.derivatives_in_span(span, u, &mut value);
                    value[0]
                }
                None => curve.point_unchecked(u),
            };
            ClosestPoint {
                parameter: u,
                point,
                distance: distance(point, q),
            }
        };
        let mut measured: SmallVec<[ClosestPoint; 8]> = self
            .candidates
            .iter()
            .filter(|&&(_, v)| v <= limit)
            .map(|&(u, _)| measure(u, None))
            .collect();
        if measured.is_empty() {
            measured.push(measure(fallback, None));
        }
        measured.sort_by(|a, b| {
            a.distance
                .total_cmp(&b.distance)
                .then(a.parameter.total_cmp(&b.parameter))
        });
        measured.dedup_by(|a, b| a.parameter == b.parameter);
        // Polishing pays only where the Bernstein values may have missed a nearer point: the
        // least distance within their noise of zero, or a part left unresolved.
        let nearest = measured[0].distance;
        let unresolved = nearest * nearest <= SQUARED_NOISE * (self.size + nearest).powi(2);
        let polished = if unresolved || self.exhausted {
            MAX_POLISHED
        } else {
            0
        };
        let starts: SmallVec<[ClosestPoint; MAX_POLISHED]> =
            measured.iter().take(polished).copied().collect();
        for start in starts {
            // The pieces holding `u`: one, or two where it is a piece's end. A polished point
            // counts only where it is nearer than its start.
            let u = start.parameter;
            let first = pieces.partition_point(|piece| piece.end_parameter < u);
            for piece in pieces[first..].iter().take_while(|piece| piece.lo <= u) {
                let polished = measure(polish(curve, q, u, piece), Some(piece.span));
                if polished.distance < start.distance {
                    measured.push(polished);
                }
            }
        }
        let least = measured
            .iter()
            .map(|c| c.distance)
            .fold(f64::INFINITY, f64::min);
        let tie = least + CLOSEST_POINT_TOLERANCE * (self.size + least);
        measured
            .into_iter()
            .filter(|c| c.distance <= tie)
            .min_by(|a, b| a.parameter.total_cmp(&b.parameter))
            .unwrap_or(ClosestPoint {
                parameter: fallback,
                point: q,
                distance: 0.0,
            })
    }
}

/// Candidates polished at most per query (the nearest ones, measured).
const MAX_POLISHED: usize = 4;

/// Newton steps of one polish at most (bisection alone needs about 60).
const MAX_POLISH_ITERATIONS: usize = 64;

/// A polish stops after a step of at most this fraction of the piece's width (Newton's steps
/// shrink quadratically: the next one would be below rounding).
const POLISH_STEP_TOLERANCE: f64 = 1e-15;

/// The parameter near `start` in `piece` where `|s(u) - q|` is least (locally): a safeguarded
/// Newton iteration on `g(u) = (s(u) - q) · s'(u)`, `g' = |s'|² + (s(u) - q) · s''`, with the
/// bracket `[a, b]` of the piece where `g` goes from negative to positive (the distance falls,
/// then rises) shrunk at every step, and bisection when a step would leave it. Returns an end
/// of the piece when the distance only grows into it.
fn polish(curve: &Curve, q: Point, start: f64, piece: &PieceBox) -> f64 {
    let (mut a, mut b) = (piece.lo, piece.end_parameter);
    let width = b - a;
    let mut u = start.clamp(a, b);
    let mut derivatives = [[0.0; 3]; 3];
    for _ in 0..MAX_POLISH_ITERATIONS {
        curve.derivatives_in_span(piece.span, u, &mut derivatives);
        let [point, first, second] = derivatives;
        let gap: Point = std::array::from_fn(|c| point[c] - q[c]);
        let g = dot(gap, first);
        if g == 0.0 {
            break;
        }
        if g > 0.0 {
            b = u;
        } else {
            a = u;
        }
        if a >= b {
            break;
        }
        let slope = dot(first, first) + dot(gap, second);
        let newton = u - g / slope;
        let next = if slope > 0.0 && newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        let converged = (next - u).abs() <= POLISH_STEP_TOLERANCE * width;
        u = next;
        if converged {
            break;
        }
    }
    u
}

fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Fills `part` with the Bernstein coefficients of `N = |X - q W|²`, of `D = W²` (rational)
/// and of `M` (`N' D - N D'`, or `N'` up to the factor `2p` when polynomial) for the piece
/// with homogeneous Bézier points `bezier`.
///
/// Products are formed in the scaled basis `s^k (1 - s)^(d-k)` (coefficients `C(d, k)` times
/// the Bernstein ones), where a product is a plain convolution.
#[inline(always)]
fn squared_distance_coefficients<const LEN: usize>(
    bezier: &[[f64; 4]],
    q: Point,
    p: usize,
    rational: bool,
    coordinates: usize,
    part: &mut Part<LEN>,
) {
    let len = 2 * p + 1;
    let numerator = &mut part.numerator[..len];
    let mut gap = [0.0; LEN];
    for c in 0..coordinates {
        for (i, point) in bezier.iter().enumerate().take(p + 1) {
            gap[i] = BINOMIAL[p][i] * (point[c] - q[c] * point[3]);
        }
        convolve(&gap[..=p], &gap[..=p], numerator, 1.0);
    }
    unscale(numerator);
    if !rational {
        for k in 0..2 * p {
            part.slope[k] = part.numerator[k + 1] - part.numerator[k];
        }
        return;
    }
    let mut weights = [0.0; LEN];
    for (i, point) in bezier.iter().enumerate().take(p + 1) {
        weights[i] = BINOMIAL[p][i] * point[3];
    }
    let denominator = &mut part.denominator[..len];
    convolve(&weights[..=p], &weights[..=p], denominator, 1.0);
    unscale(denominator);
    // Derivatives (degree 2p - 1) scaled by C(2p - 1, k), the values by C(2p, k); the
    // product has degree 4p - 1.
    let degree = 2 * p;
    let mut numerator_slope = [0.0; LEN];
    let mut denominator_slope = [0.0; LEN];
    let mut numerator_scaled = [0.0; LEN];
    let mut denominator_scaled = [0.0; LEN];
    for k in 0..degree {
        let scale = degree as f64 * BINOMIAL[degree - 1][k];
        numerator_slope[k] = scale * (part.numerator[k + 1] - part.numerator[k]);
        denominator_slope[k] = scale * (part.denominator[k + 1] - part.denominator[k]);
    }
    for k in 0..=degree {
        numerator_scaled[k] = BINOMIAL[degree][k] * part.numerator[k];
        denominator_scaled[k] = BINOMIAL[degree][k] * part.denominator[k];
    }
    let slope = &mut part.slope[..2 * degree];
    convolve(
        &numerator_slope[..degree],
        &denominator_scaled[..=degree],
        slope,
        1.0,
    );
    convolve(
        &numerator_scaled[..=degree],
        &denominator_slope[..degree],
        slope,
        -1.0,
    );
    unscale(slope);
}

/// Sign changes in a sequence, zeros skipped.
fn sign_changes(values: &[f64]) -> usize {
    let mut changes = 0;
    let mut previous = 0.0;
    for &v in values {
        if v != 0.0 {
            if previous != 0.0 && (v > 0.0) != (previous > 0.0) {
                changes += 1;
            }
            previous = v;
        }
    }
    changes
}

/// The root in `[0, 1]` of the Bernstein polynomial `coefficients`, which is `<= 0` at 0 and
/// `>= 0` at 1 with a single sign change: Newton's method, falling back to bisection whenever
/// a step leaves the bracket.
fn upward_root(coefficients: &[f64]) -> f64 {
    let (mut below, mut above) = (0.0f64, 1.0f64);
    // Start where the control polygon crosses zero: close to the root, since the polygon
    // converges to the polynomial.
    let degree = (coefficients.len() - 1).max(1) as f64;
    let mut s = 0.5;
    for (k, pair) in coefficients.windows(2).enumerate() {
        if pair[0] < 0.0 && pair[1] >= 0.0 {
            s = (k as f64 + pair[0] / (pair[0] - pair[1])) / degree;
            break;
        }
    }
    if !(s > 0.0 && s < 1.0) {
        s = 0.5;
    }
    for _ in 0..MAX_ROOT_ITERATIONS {
        let (value, slope) = value_and_slope(coefficients, s);
        if value == 0.0 {
            return s;
        }
        if value < 0.0 {
            below = s;
        } else {
            above = s;
        }
        let newton = s - value / slope;
        // Converged when the step no longer moves `s` by more than rounding.
        if (newton - s).abs() <= ROOT_STEP_TOLERANCE {
            return newton.clamp(below, above);
        }
        if slope > 0.0 && newton > below && newton < above {
            s = newton;
        } else {
            let middle = 0.5 * (below + above);
            if middle <= below || middle >= above {
                break;
            }
            s = middle;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::CurveLimits;

    fn curve(degree: usize, points: &[&[f64]], knots: &[f64], weights: Option<&[f64]>) -> Curve {
        let points: Vec<Vec<f64>> = points.iter().map(|p| p.to_vec()).collect();
        Curve::new(degree, &points, knots, weights, &CurveLimits::default()).unwrap()
    }

    #[test]
    fn sign_changes_skip_zeros() {
        assert_eq!(sign_changes(&[-1.0, 0.0, 2.0, 3.0]), 1);
        assert_eq!(sign_changes(&[1.0, -1.0, 0.0, 1.0]), 2);
        assert_eq!(sign_changes(&[0.0, 0.0]), 0);
    }

    #[test]
    fn upward_root_of_a_line_and_a_cubic() {
        // 2s - 1 in Bernstein form: coefficients -1, 1.
        assert!((upward_root(&[-1.0, 1.0]) - 0.5).abs() < 1e-15);
        // (s - 0.3)³ = Σ c_k B_k with blossoms c_k = (0 - .3)^(3-k) (1 - .3)^k, the root 0.3.
        let c: Vec<f64> = (0..4)
            .map(|k| (-0.3f64).powi(3 - k) * 0.7f64.powi(k))
            .collect();
        assert!((upward_root(&c) - 0.3).abs() < 1e-5);
    }

    #[test]
    fn polishing_finds_the_foot_of_a_query_next_to_the_curve() {
        // The unit quarter circle: the foot of q = (1 + ε)(cos θ, sin θ) is at angle θ, at
        // distance ε, whatever the start within the piece.
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let arc = curve(
            2,
            &[&[1.0, 0.0], &[1.0, 1.0], &[0.0, 1.0]],
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Some(&[1.0, w, 1.0]),
        );
        let search = ClosestPointSearch::new(&arc, None).unwrap();
        let piece = &search.pieces[0];
        for epsilon in [1e-3, 1e-9, 1e-14] {
            let theta: f64 = 0.7;
            let q = [
                (1.0 + epsilon) * theta.cos(),
                (1.0 + epsilon) * theta.sin(),
                0.0,
            ];
            for start in [0.0, 0.2, 0.9, 1.0] {
                let u = polish(&arc, q, start, piece);
                let point = arc.point(u).unwrap();
                let gap = distance(point, q);
                assert!(
                    (gap - epsilon).abs() <= 4e-16,
                    "ε {epsilon}, start {start}: {gap}"
                );
                let angle = point[1].atan2(point[0]);
                assert!(
                    (angle - theta).abs() <= 1e-8,
                    "ε {epsilon}, start {start}: {angle}"
                );
            }
        }
    }

    #[test]
    fn a_quarter_circle_from_its_centre_ties_to_the_range_start() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let arc = curve(
            2,
            &[&[1.0, 0.0], &[1.0, 1.0], &[0.0, 1.0]],
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            Some(&[1.0, w, 1.0]),
        );
        let search = ClosestPointSearch::new(&arc, None).unwrap();
        let found = search.closest([0.0, 0.0, 0.0]);
        assert_eq!(found.parameter, 0.0);
        assert!((found.distance - 1.0).abs() < 1e-14);
        let inner = ClosestPointSearch::new(&arc, Some((0.25, 0.75))).unwrap();
        assert_eq!(inner.closest([0.0, 0.0, 0.0]).parameter, 0.25);
    }
}
