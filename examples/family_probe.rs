use knotshape::shape::ShapeQuery;
use knotshape::shape::family::{FamilyChoice, solve_families};
use knotshape::spline::{Curve, CurveLimits};
fn main() {
    let points: Vec<Vec<f64>> = [
        [0.0, 0.0],
        [1.0, 1.5],
        [2.0, 2.5],
        [3.2, 3.0],
        [4.5, 2.8],
        [5.5, 1.8],
        [6.3, 0.6],
        [7.5, 0.2],
        [8.8, 0.9],
        [9.8, 2.2],
        [11.0, 3.0],
        [12.2, 2.6],
        [13.0, 1.2],
        [14.0, 0.0],
        [15.0, 0.5],
        [16.0, 2.0],
    ]
    .iter()
    .map(|p| p.to_vec())
    .collect();
    let mut knots = vec![0.0; 6];
    knots.extend((0..10).map(|i| ((0.08 + 0.84 * i as f64 / 9.0) * 1e4).round() / 1e4));
    knots.extend([1.0; 6]);
    let curve = Curve::new(5, &points, &knots, None, &CurveLimits::default()).unwrap();
    let n: usize = std::env::args().nth(1).map_or(20, |s| s.parse().unwrap());
    let mut count = 0;
    for k in 0..n {
        let t = 0.3 + 0.4 * ((k % 7) as f64 / 7.0);
        let p = curve.point(t).unwrap();
        let a = k as f64 * 0.7;
        let target = [p[0] + 0.15 * a.cos(), p[1] + 0.15 * a.sin(), 0.0];
        let q = ShapeQuery::new(&curve, t);
        count += solve_families(&q, FamilyChoice::Default, target)
            .solutions
            .len();
    }
    println!("{count}");
}
