//! The closest point of a surface to a query point: the global minimum of the distance over a
//! parameter rectangle, its edges and corners included — the curves' search
//! ([`crate::spline::ClosestPointSearch`]) in two variables.
//!
//! The rectangle is cut into Bézier patches, one per pair of knot spans (blossoming per
//! direction). On a patch with homogeneous Bézier points `(X_rs, W_rs)` and local parameters
//! `(σ, τ) ∈ [0, 1]²`, the squared distance to `q` is `g = N / D` with `N = |X − q W|²`
//! (bidegree `(2p, 2q)`) and `D = W²` (`D = 1` for polynomial surfaces), both in Bernstein form.
//! Every coefficient of `D` is positive (positive weights), so `g >= min_k N_k / D_k` on the
//! patch (the convex hull property), a lower bound that tightens with the square of the size as
//! a part is halved.
//!
//! The patches' bounding boxes form a hierarchy ([`crate::spline::box_tree`], the curves'
//! own); the search takes boxes and parts of patches best first (least lower bound first,
//! [`BinaryHeap`]) and drops every one that cannot come within the tolerance of the best
//! distance found. A part is *resolved* without halving when `P_μ = N − μ D` (`μ` the best
//! squared distance so far) is strictly convex on it — certified from the Bernstein
//! coefficients of its second derivatives: `P_σσ >= a > 0`, `P_ττ >= b > 0`, `|P_στ| <= c`,
//! `a b > c²` — then a projected Newton iteration finds the minimum `x̂` of `P_μ` on the part,
//! `x̂` is offered, and convexity gives the certified bound
//! `P_μ >= P_μ(x̂) + Σ_i min(∂_i P_μ(x̂) (0 − x̂_i), ∂_i P_μ(x̂) (1 − x̂_i))` on the whole part; when
//! that bound is not below zero (within the rounding noise) no point of the part is nearer
//! than `√μ`; otherwise `μ` takes `g(x̂)` and the step repeats (Dinkelbach's iteration for the
//! ratio `N / D`). Parts that are not resolved are halved (de Casteljau) in the variable whose
//! second derivative bound is larger. Corners are offered as they appear (a Bézier net's
//! corners are points of the surface).
//!
//! The candidates within the tolerance are then measured with the surface evaluator, the
//! nearest polished by Newton's method on the exact partials inside its patch (and more of
//! them when the query lies within the Bernstein values' noise of the surface, or the work
//! budget ran out), and among those within [`SURFACE_CLOSEST_TOLERANCE`] of the least
//! distance the smallest `(u, v)` (`u` first) is the answer. Work per query is bounded
//! ([`MAX_SUBDIVISIONS`] halvings).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::patches::PatchRect;
use super::surface::{Direction, Surface};
use crate::spline::box_tree::{self, BoxItem, BoxNode, NodeContent};
use crate::spline::vector::distance;
use crate::spline::{ClosestPointSearch, Point};

/// Ties and precision: among points whose distances lie within
/// `SURFACE_CLOSEST_TOLERANCE · (size + d) + COORDINATE_ROUNDING · magnitude` of the least
/// distance `d` (`size`: the diagonal of the control points' bounding box; `magnitude`: their
/// largest coordinate, whose rounding every evaluated point carries), the smallest `(u, v)`
/// is returned (`u` first).
pub const SURFACE_CLOSEST_TOLERANCE: f64 = 1e-12;

/// The rounding of a point evaluated far from the origin, relative to the largest
/// coordinate: a few units in the last place (see [`SURFACE_CLOSEST_TOLERANCE`]).
pub const COORDINATE_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// Rounding allowance of the Bernstein values of the squared distance, relative to
/// `(size + d)²` (as for the curves).
const SQUARED_NOISE: f64 = 64.0 * f64::EPSILON;

/// Halvings of one patch in one variable at most: its parts are then `2^-52` of it.
const MAX_DEPTH: u32 = 52;

/// Halvings per query at most, which bounds the time whatever the input.
pub const MAX_SUBDIVISIONS: usize = 16_384;

/// Dinkelbach steps per part at most before it is halved instead.
const MAX_RATIO_STEPS: usize = 4;

/// Candidates polished at most per query (the nearest ones, measured).
const MAX_POLISHED: usize = 4;

/// Why a closest-point search cannot run: a `range` end (`direction`, index 0 or 1) at fault.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum SurfaceRangeError {
    #[error("range end {} of {} is not a finite number", index, direction.name())]
    NonFinite { direction: Direction, index: usize },
    #[error("{} = {value} lies outside the domain [{}, {}]", direction.name(), domain.0, domain.1)]
    OutsideDomain {
        direction: Direction,
        index: usize,
        value: f64,
        domain: (f64, f64),
    },
    #[error("the {} range [{lo}, {hi}] is reversed: its first value must not exceed its second", direction.name())]
    Reversed {
        direction: Direction,
        lo: f64,
        hi: f64,
    },
}

impl SurfaceRangeError {
    /// The direction (0 for `u`, 1 for `v`) and the end (0 or 1) at fault.
    pub fn position(&self) -> (usize, usize) {
        let (direction, index) = match *self {
            SurfaceRangeError::NonFinite { direction, index }
            | SurfaceRangeError::OutsideDomain {
                direction, index, ..
            } => (direction, index),
            SurfaceRangeError::Reversed { direction, .. } => (direction, 0),
        };
        (usize::from(direction == Direction::V), index)
    }
}

/// The closest point found for one query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceClosestPoint {
    /// The parameters of the closest point.
    pub u: f64,
    pub v: f64,
    /// `S(u, v)`.
    pub point: Point,
    /// `|S(u, v) − q|`.
    pub distance: f64,
}

/// One patch of the searched rectangle: its rectangle and the parameters that stand for its
/// upper edges (the float below a knot where the surface jumps there).
#[derive(Debug, Clone, Copy)]
struct Patch {
    rect: PatchRect,
    ends: (f64, f64),
}

/// A surface's rectangle cut into Bézier patches, ready for many queries.
#[derive(Debug, Clone)]
pub struct SurfaceClosestSearch<'s> {
    surface: &'s Surface,
    range: [(f64, f64); 2],
    patches: Vec<Patch>,
    /// Homogeneous Bézier points, `(p + 1)(q + 1)` per patch.
    nets: Vec<[f64; 4]>,
    nodes: Vec<BoxNode<(f64, f64)>>,
    size: f64,
    /// The largest control-point coordinate magnitude.
    magnitude: f64,
    /// For a rectangle of zero width: the iso-curve along the other direction and the fixed
    /// direction and value.
    line: Option<(Direction, f64)>,
}

impl<'s> SurfaceClosestSearch<'s> {
    /// Cuts `range` (default: the whole domain; each end just outside its direction's domain
    /// taken as its end, a periodic direction's reduced into the period) of `surface` into
    /// Bézier patches.
    pub fn new(
        surface: &'s Surface,
        range: Option<[(f64, f64); 2]>,
    ) -> Result<Self, SurfaceRangeError> {
        let range = checked_range(surface, range)?;
        let (p, q) = (surface.u().degree(), surface.v().degree());
        let line = if range[0].0 == range[0].1 {
            Some((Direction::U, range[0].0))
        } else if range[1].0 == range[1].1 {
            Some((Direction::V, range[1].0))
        } else {
            None
        };
        let jumps = [surface.u().jump_knots(), surface.v().jump_knots()];
        let below = |x: f64, direction: usize| {
            if jumps[direction].contains(&x) {
                float_below(x)
            } else {
                x
            }
        };
        let mut patches = Vec::new();
        let mut nets = Vec::new();
        let mut items = Vec::new();
        if line.is_none() {
            let size = (p + 1) * (q + 1);
            let mut net = vec![[0.0; 4]; size];
            for rect in surface.patch_rects(range) {
                surface.bezier_net(&rect, &mut net);
                let (mut min, mut max) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
                for h in &net {
                    for c in 0..3 {
                        let x = h[c] / h[3];
                        min[c] = min[c].min(x);
                        max[c] = max[c].max(x);
                    }
                }
                items.push(BoxItem {
                    min,
                    max,
                    key: (rect.u.0, rect.v.0),
                });
                nets.extend_from_slice(&net);
                patches.push(Patch {
                    rect,
                    ends: (below(rect.u.1, 0), below(rect.v.1, 1)),
                });
            }
        }
        Ok(SurfaceClosestSearch {
            surface,
            range,
            patches,
            nets,
            nodes: box_tree::build(&items),
            size: surface.size(),
            magnitude: surface.coordinate_magnitude(),
            line,
        })
    }

    /// The rectangle searched.
    pub fn range(&self) -> [(f64, f64); 2] {
        self.range
    }

    /// The closest point of the rectangle to `q`: the global minimum of `|S(u, v) − q|`
    /// (module docs), the smallest `(u, v)` among ties within [`SURFACE_CLOSEST_TOLERANCE`].
    pub fn closest(&self, q: Point) -> SurfaceClosestPoint {
        if let Some((fixed, value)) = self.line {
            return self.closest_on_line(q, fixed, value);
        }
        let mut search = Search::new(self, q);
        let mut heap = BinaryHeap::new();
        if let Some(root) = self.nodes.first() {
            heap.push(Entry {
                bound: root.squared_distance(q, 3),
                key: root.from,
                what: What::Node(0),
            });
        }
        while let Some(entry) = heap.pop() {
            if entry.bound > search.best + search.slack {
                // Least bound first: nothing left can come within the tolerance.
                break;
            }
            if search.prunes(entry.bound, entry.key) {
                continue;
            }
            match entry.what {
                What::Node(index) => match self.nodes[index].content {
                    NodeContent::Halves(left, right) => {
                        for child in [left, right] {
                            let node = &self.nodes[child];
                            heap.push(Entry {
                                bound: node.squared_distance(q, 3),
                                key: node.from,
                                what: What::Node(child),
                            });
                        }
                    }
                    NodeContent::Item(patch) => {
                        if let Some(part) = search.start_patch(patch) {
                            heap.push(part);
                        }
                    }
                },
                What::Part(part) => search.process(part, &mut heap),
            }
        }
        search.finish()
    }

    /// The closest point when the rectangle is one line: the curves' search on the iso-curve.
    fn closest_on_line(&self, q: Point, fixed: Direction, value: f64) -> SurfaceClosestPoint {
        let curve = self.surface.iso_curve(fixed, value);
        let other = match fixed {
            Direction::U => self.range[1],
            Direction::V => self.range[0],
        };
        let found = ClosestPointSearch::new(&curve, Some(other))
            .map(|search| search.closest(q))
            .ok();
        let t = found.map_or(other.0, |f| f.parameter);
        let (u, v) = match fixed {
            Direction::U => (value, t),
            Direction::V => (t, value),
        };
        let point = self.surface.point(u, v);
        SurfaceClosestPoint {
            u,
            v,
            point,
            distance: distance(point, q),
        }
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

/// `range` checked against the domain (module docs of [`SurfaceClosestSearch::new`]).
fn checked_range(
    surface: &Surface,
    range: Option<[(f64, f64); 2]>,
) -> Result<[(f64, f64); 2], SurfaceRangeError> {
    let domain = surface.domain();
    let range = range.unwrap_or(domain);
    let mut out = domain;
    for (k, direction) in [Direction::U, Direction::V].into_iter().enumerate() {
        let axis = surface.axis(direction);
        let mut ends = [range[k].0, range[k].1];
        for (index, value) in ends.iter_mut().enumerate() {
            if !value.is_finite() {
                return Err(SurfaceRangeError::NonFinite { direction, index });
            }
            *value = axis.snap(*value).ok_or(SurfaceRangeError::OutsideDomain {
                direction,
                index,
                value: *value,
                domain: domain[k],
            })?;
        }
        if ends[0] > ends[1] {
            return Err(SurfaceRangeError::Reversed {
                direction,
                lo: ends[0],
                hi: ends[1],
            });
        }
        out[k] = (ends[0], ends[1]);
    }
    Ok(out)
}

/// What a heap entry stands for.
#[derive(Debug, Clone, Copy)]
enum What {
    Node(usize),
    Part(usize),
}

/// A heap entry: the lower bound of the squared distance on a box or part, and its smallest
/// `(u, v)`; ordered so that the least bound comes first.
#[derive(Debug, Clone, Copy)]
struct Entry {
    bound: f64,
    key: (f64, f64),
    what: What,
}

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed: `BinaryHeap` pops the greatest.
        other
            .bound
            .total_cmp(&self.bound)
            .then(other.key.0.total_cmp(&self.key.0))
            .then(other.key.1.total_cmp(&self.key.1))
    }
}

/// A part `[s0, s1] × [t0, t1]` of a patch (in the patch's local parameters) and where its
/// Bernstein coefficients of `N` and `D` live in the search's arena.
#[derive(Debug, Clone, Copy)]
struct Part {
    patch: usize,
    block: usize,
    s: (f64, f64),
    t: (f64, f64),
    depth: (u32, u32),
}

mod search;
use search::Search;
