//! Differential geometry at a point: the unit normal (with its limit where the
//! parametrisation degenerates) and the curvatures of the fundamental forms.
//!
//! * Normal: `n = S_u × S_v / |S_u × S_v|`. Where `|S_u × S_v|` vanishes (within
//!   [`NORMAL_DEGENERACY`] of the partials' scales, e.g. a row of control points collapsed
//!   into a pole), the normal is the limit from inside the domain: if `S_u` vanishes,
//!   `S_u(u, v + δ) ≈ δ S_uv`, so `n ∝ σ S_uv × S_v` with `σ` the sign of the step `δ` that
//!   points into the domain (`+1` except at the end of the `v` domain); if `S_v` vanishes,
//!   `n ∝ σ S_u × S_uv` likewise in `u`. When that limit vanishes too (both partials zero, or
//!   parallel and non-zero), there is no normal: `None`.
//! * Curvature, with `E = S_u·S_u`, `F = S_u·S_v`, `G = S_v·S_v`, `L = S_uu·n`, `M = S_uv·n`,
//!   `N = S_vv·n` (do Carmo §3.3): Gaussian `K = (LN − M²) / (EG − F²)`, mean
//!   `H = (EN − 2FM + GL) / (2 (EG − F²))`, principal `k1,2 = H ± √(H² − K)` (`k1 >= k2`;
//!   positive where the surface bends towards `n`), their directions the eigenvectors
//!   `a S_u + b S_v` of the shape operator `I⁻¹ II`, unit and orthogonal
//!   (`d2 = n × d1`). At an umbilic (`k1 = k2` within [`UMBILIC_TOLERANCE`]) every tangent
//!   direction is principal: `d1 = S_u / |S_u|`. Only where the normal is regular
//!   (`EG − F² > 0`): at a degenerate point the curvature is `None`.

use super::eval::Partials;
use crate::spline::Point;
use crate::spline::vector::{cross, dot, norm, scale, sub};

/// `|S_u × S_v|` at most this fraction of `scale_u · scale_v` (the partials' hodograph
/// scales, [`Partials::scales`]) counts as zero: the parametrisation degenerates there.
pub const NORMAL_DEGENERACY: f64 = 1e-12;

/// `H² − K` at most this fraction of `H²` (or of `|K|`) is an umbilic.
pub const UMBILIC_TOLERANCE: f64 = 1e-12;

/// Where a parameter lies in its direction's domain: the side a step into the domain takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Inward {
    /// Inside the domain or at its start: steps go up (`δ > 0`).
    Up,
    /// At the end of the domain: steps go down (`δ < 0`).
    Down,
}

impl Inward {
    /// `+1` or `-1`.
    fn sign(self) -> f64 {
        match self {
            Inward::Up => 1.0,
            Inward::Down => -1.0,
        }
    }

    /// [`Inward::Down`] exactly at the domain's end `hi`.
    pub fn of(t: f64, hi: f64) -> Inward {
        if t >= hi { Inward::Down } else { Inward::Up }
    }
}

/// How a normal was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NormalKind {
    /// `S_u × S_v` normalised.
    Regular,
    /// The limit at a degenerate point (module docs).
    Limit,
}

/// The unit normal at a point whose partials up to order 2 are `partials`, `inward` telling
/// which way steps into the domain go in `u` and `v` (module docs); `None` where there is none.
pub fn unit_normal(partials: &Partials, inward: [Inward; 2]) -> Option<(Point, NormalKind)> {
    let [scale_u, scale_v] = partials.scales;
    let (du, dv) = (partials.du(), partials.dv());
    let duv = partials.values[1][1];
    let threshold = NORMAL_DEGENERACY * scale_u * scale_v;
    let regular = cross(du, dv);
    if norm(regular) > threshold {
        return Some((normalised(regular), NormalKind::Regular));
    }
    let tiny_u = norm(du) <= NORMAL_DEGENERACY.sqrt() * scale_u;
    let tiny_v = norm(dv) <= NORMAL_DEGENERACY.sqrt() * scale_v;
    let candidates = [
        (tiny_u, scale(cross(duv, dv), inward[1].sign())),
        (tiny_v, scale(cross(du, duv), inward[0].sign())),
    ];
    candidates
        .into_iter()
        .filter(|&(applies, limit)| applies && norm(limit) > threshold)
        .map(|(_, limit)| (normalised(limit), NormalKind::Limit))
        .next()
}

fn normalised(v: Point) -> Point {
    scale(v, 1.0 / norm(v))
}

/// Curvatures at a regular point (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    /// `K = k1 k2`.
    pub gaussian: f64,
    /// `H = (k1 + k2) / 2`.
    pub mean: f64,
    /// `[k1, k2]`, `k1 >= k2`.
    pub principal: [f64; 2],
    /// The unit principal directions (3D tangent vectors), orthogonal.
    pub directions: [Point; 2],
}

/// The curvatures at a point with partials up to order 2 and a regular unit normal `n`
/// (module docs); `None` where `EG − F²` vanishes.
pub fn curvature(partials: &Partials, normal: Point) -> Option<Curvature> {
    let (du, dv) = (partials.du(), partials.dv());
    let [[_, _, dvv], [_, duv, _], [duu, _, _]] = partials.values;
    let (e, f, g) = (dot(du, du), dot(du, dv), dot(dv, dv));
    let area = norm(cross(du, dv));
    let [scale_u, scale_v] = partials.scales;
    if area.is_nan() || area <= NORMAL_DEGENERACY * scale_u * scale_v {
        return None;
    }
    let determinant = area * area;
    let (l, m, n) = (dot(duu, normal), dot(duv, normal), dot(dvv, normal));
    let gaussian = (l * n - m * m) / determinant;
    let mean = (e * n - 2.0 * f * m + g * l) / (2.0 * determinant);
    let spread = mean * mean - gaussian;
    let umbilic = spread <= UMBILIC_TOLERANCE * (mean * mean).max(gaussian.abs());
    let root = if umbilic { 0.0 } else { spread.sqrt() };
    let principal = [mean + root, mean - root];
    let first = if umbilic {
        normalised(du)
    } else {
        let k = principal[0];
        // A row of (I⁻¹ II − k) = 0 written as II − k I: (L − kE) a + (M − kF) b = 0, or
        // (M − kF) a + (N − kG) b = 0; the better conditioned of the two.
        let (r0, r1) = ((l - k * e, m - k * f), (m - k * f, n - k * g));
        let (a, b) = if r0.0.abs() + r0.1.abs() >= r1.0.abs() + r1.1.abs() {
            (-r0.1, r0.0)
        } else {
            (r1.1, -r1.0)
        };
        let direction = std::array::from_fn(|c| a * du[c] + b * dv[c]);
        if norm(direction) > 0.0 {
            normalised(direction)
        } else {
            normalised(du)
        }
    };
    // Keep it tangent (remove any rounding along n), then the second one orthogonal.
    let first = normalised(sub(first, scale(normal, dot(first, normal))));
    let second = cross(normal, first);
    Some(Curvature {
        gaussian,
        mean,
        principal,
        directions: [first, second],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::KnotForm;
    use crate::surface::{Surface, SurfaceLimits};

    /// A rational biquadratic patch of the unit sphere's octant `x, y, z >= 0` (The NURBS
    /// Book, Ex. 8.? form): the quarter circle in the `xz` plane swept around `z`. Its row
    /// `i = 2` (at the pole `(0, 0, 1)`) collapses: `S_v = 0` there.
    fn octant() -> Surface {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        // Meridian (x, z) from the equator to the pole, weights 1, w, 1.
        let meridian = [([1.0, 0.0], 1.0), ([1.0, 1.0], w), ([0.0, 1.0], 1.0)];
        // The equator's quarter circle (x, y) with weights 1, w, 1.
        let circle = [([1.0, 0.0], 1.0), ([1.0, 1.0], w), ([0.0, 1.0], 1.0)];
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for (xz, wm) in meridian {
            let mut row = Vec::new();
            let mut row_weights = Vec::new();
            for (xy, wc) in circle {
                row.push(vec![xz[0] * xy[0], xz[0] * xy[1], xz[1]]);
                row_weights.push(wm * wc);
            }
            points.push(row);
            weights.push(row_weights);
        }
        let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        Surface::from_knot_forms(
            (2, 2),
            &points,
            (KnotForm::Flat(&knots), KnotForm::Flat(&knots)),
            Some(&weights),
            &SurfaceLimits::default(),
        )
        .unwrap()
    }

    #[test]
    fn the_sphere_has_radial_normals_and_unit_curvatures() {
        let sphere = octant();
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (0.5, 0.5), (0.9, 0.1), (0.99, 1.0)] {
            let partials = sphere.partials(u, v, 2);
            let point = partials.point();
            assert!((norm(point) - 1.0).abs() < 1e-14);
            let (normal, kind) = unit_normal(&partials, [Inward::Up; 2]).unwrap();
            assert_eq!(kind, NormalKind::Regular);
            // The normal S_u × S_v: u runs up the meridian, v around z; it points inwards.
            let along = dot(normal, point);
            assert!((along.abs() - 1.0).abs() < 1e-13, "{along}");
            let curvature = curvature(&partials, normal).unwrap();
            let k = -along.signum();
            assert!((curvature.gaussian - 1.0).abs() < 1e-12);
            assert!((curvature.mean - k).abs() < 1e-12);
            assert!((curvature.principal[0] - k).abs() < 1e-6);
            assert!((curvature.principal[1] - k).abs() < 1e-6);
            let [d1, d2] = curvature.directions;
            assert!(dot(d1, d2).abs() < 1e-14 && dot(d1, normal).abs() < 1e-14);
        }
    }

    #[test]
    fn the_pole_has_the_limit_normal_and_no_curvature() {
        let sphere = octant();
        for v in [0.0, 0.4, 1.0] {
            let partials = sphere.partials(1.0, v, 2);
            assert!(norm(partials.dv()) < 1e-15, "the pole row collapses");
            let (normal, kind) =
                unit_normal(&partials, [Inward::Down, Inward::of(v, 1.0)]).unwrap();
            assert_eq!(kind, NormalKind::Limit);
            // Nearby normals (just inside the domain) agree with the limit.
            let near = sphere.partials(1.0 - 1e-6, v, 2);
            let (nearby, _) = unit_normal(&near, [Inward::Up; 2]).unwrap();
            assert!(norm(sub(normal, nearby)) < 1e-5, "{normal:?} vs {nearby:?}");
            assert!((normal[2].abs() - 1.0).abs() < 1e-12);
            assert!(curvature(&partials, normal).is_none());
        }
    }
}
