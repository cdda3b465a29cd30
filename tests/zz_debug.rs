#![allow(clippy::unwrap_used)]
mod common;
use common::families::*;
use knotshape::shape::family::{Family, FamilyChoice, solve_families};
use knotshape::spline::{Curve, CurveLimits};

#[test]
fn debug_triple() {
    let knots = [1.161160488216983, 1.161160488216983, 1.161160488216983, 1.161160488216983, 1.161160488216983, 1.843120492388275, 2.6994690958241465, 3.5788545640360696, 3.5788545640360696, 3.988827964137272, 4.620830659395404, 4.620830659395404, 4.620830659395404, 4.620830659395404, 4.620830659395404];
    let points = [[4.552044003190719, 3.256351300404594, 3.490152110583802], [-2.1867453512558788, -2.4001983549974035, -4.208124664511594], [-4.696134951368144, 4.404351982666185, 0.742009833643217], [-4.41737026563636, -4.236832328540306, -4.50868988224392], [4.679258197397715, -3.7765722490161435, -2.282589975575211], [3.937015666137338, 4.940634086818157, 4.580221945938726], [-4.153262257130006, -3.879951724236772, -2.7457406240068396], [1.0927110432142193, -0.43164151195480205, -0.534684072416157], [-4.356456929079383, -4.769836748853948, 2.296402368745719], [-4.993291269241492, 4.592173624392828, -3.94989097911973]];
    let curve = Curve::new(4, &points, &knots, None, &CurveLimits::default()).unwrap();
    let t = 3.5788545640360696;
    let problem = setup(&curve, t, Family::Triples, None, true).unwrap();
    let x = [2.965216371162596, 3.0941373349122956, 4.553747743138858];
    let k = problem.knots_with(&[6, 7, 9], &x);
    let target = common::de_boor(&curve, &k, t).unwrap();
    let choice = FamilyChoice::Only { envelope: false, direct: false, triples: true };
    let out = solve_families(&query(&curve, t, None, true), choice, target);
    println!("answer {:?}", answers_of(&out.solutions, &problem, &[6, 7, 9]).iter().map(|s| [s.knots[6], s.knots[7], s.knots[9]]).collect::<Vec<_>>());
    let sbox = SetBox::new(&problem, &[6,7,9]).unwrap();
    println!("box {:?} {:?} span {}", sbox.lo, sbox.hi, problem.span);
    let brute = brute_force(&Net::of(&curve), &problem, &sbox, target, BruteOptions::triples());
    println!("brute {:?}", brute.roots.iter().map(|r| (&r.x, r.inside, r.conditioning)).collect::<Vec<_>>());
}
