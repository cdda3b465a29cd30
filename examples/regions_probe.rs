use knotshape::shape::family::{FamilyChoice, family_regions};
use knotshape::shape::{PolygonOptions, ShapeQuery};
use knotshape::spline::{Curve, CurveLimits, KnotForm};
fn main() {
    let pts = [
        [6.299319346658269, 3.455900175625965],
        [1.9015410332208802, 0.5540642207021982],
        [-9.288422262658075, -2.220768120556034],
        [-7.843636610940687, 7.467041723793603],
        [-9.919407604620185, 9.658039351229966],
        [-7.411780633427414, -9.257695663843862],
        [-1.0262597315848705, -2.307289488136721],
        [-4.949600342350726, 9.270060815686179],
        [-9.845902437519754, 0.5580117918366039],
    ];
    let mut knots = vec![0.0];
    knots.extend([
        0.0, 0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0,
    ]);
    knots.push(1.0);
    let curve = Curve::new(4, &pts, &knots, None, &CurveLimits::default()).unwrap();
    let _ = KnotForm::Flat(&knots);
    let q = ShapeQuery::new(&curve, 0.27946934612270313);
    let start = std::time::Instant::now();
    let (c, f) = family_regions(
        &q,
        FamilyChoice::Default,
        PolygonOptions {
            tolerance: Some(0.001),
            max_vertices: 4096,
        },
    );
    let rings: usize = f
        .iter()
        .map(|g| {
            g.regions
                .iter()
                .map(|r| r.outline.rings.len())
                .sum::<usize>()
        })
        .sum();
    let folded: usize = f
        .iter()
        .map(|g| g.regions.iter().filter(|r| r.outline.folded).count())
        .sum();
    let regions: usize = f.iter().map(|g| g.regions.len()).sum();
    println!(
        "{} candidates, {} regions, {} folded, {} rings in {:?}",
        c.len(),
        regions,
        folded,
        rings,
        start.elapsed()
    );
}
