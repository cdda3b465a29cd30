//! Driver for `benches/edit_instructions.sh`: runs one edit benchmark case `COUNT` times
//! (the cases of `benches/solve.rs`' `edit` group). Run under callgrind it gives
//! instructions per call, which, unlike time, hardly change with the machine's load.
//!
//! Usage: `edit_cost CASE COUNT`, CASE one of `knots`, `weights`, `weights_without_deviation`,
//! `all`, `all_without_deviation`, `constrained`, `constrained_without_deviation`.
#![allow(clippy::unwrap_used)]

#[path = "support/edit_cases.rs"]
mod edit_cases;

use std::hint::black_box;

use edit_cases::{ALL, EXAMPLE_PARAMETER, EXAMPLE_TARGET, constrained_case, example_curve};
use knotshape::shape::{
    ConstraintSet, EditContext, EditOptions, FixedPoles, MethodKind, PoleVariables, ShapeQuery,
    constrained_control_point_move, edit,
};

fn main() {
    let mut args = std::env::args().skip(1);
    let case = args.next().unwrap_or_default();
    let Some(count) = args.next().and_then(|n| n.parse::<usize>().ok()) else {
        eprintln!("usage: edit_cost CASE COUNT");
        std::process::exit(2);
    };
    let curve = example_curve();
    let constraints = ConstraintSet::none();
    let fixed = FixedPoles::none(curve.control_points().len());
    let variables = PoleVariables::free_poles(&fixed);
    let context = EditContext {
        query: ShapeQuery::new(&curve, EXAMPLE_PARAMETER),
        constraints: &constraints,
        fixed: &fixed,
        variables: &variables,
    };
    let constrained = constrained_case();
    let options = |measure_deviation| EditOptions {
        measure_deviation,
        nearest: false,
    };
    let run_edit = |methods: &[MethodKind], measure| {
        black_box(
            edit(
                &context,
                methods,
                black_box(&EXAMPLE_TARGET),
                options(measure),
            )
            .unwrap(),
        );
    };
    let run_move = |measure| {
        black_box(
            constrained_control_point_move(
                &constrained.curve,
                constrained.t,
                black_box(constrained.target),
                &constrained.constraints,
                &constrained.variables,
                measure,
            )
            .unwrap(),
        );
    };
    for _ in 0..count {
        match case.as_str() {
            "knots" => run_edit(&[MethodKind::Knots], true),
            "weights" => run_edit(&[MethodKind::Weights], true),
            "weights_without_deviation" => run_edit(&[MethodKind::Weights], false),
            "all" => run_edit(&ALL, true),
            "all_without_deviation" => run_edit(&ALL, false),
            "constrained" => run_move(true),
            "constrained_without_deviation" => run_move(false),
            other => {
                eprintln!("edit_cost: unknown case {other:?}");
                std::process::exit(2);
            }
        }
    }
}
