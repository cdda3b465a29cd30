//! Unit tests of the STEP reader and writer: each entity read back from what the writer wrote,
//! and the reader's answers on hand-made and broken files.

use super::*;
use crate::spline::{CurveLimits, KnotConvention};

fn limits() -> FileLimits {
    FileLimits::default()
}

fn file(data: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
    )
}

const CUBIC: &str = "#1=CARTESIAN_POINT('',(0.,0.));\n#2=CARTESIAN_POINT('',(1.,2.));\n\
    #3=CARTESIAN_POINT('',(3.,2.));\n#4=CARTESIAN_POINT('',(4.,0.E+000));\n\
    #5=B_SPLINE_CURVE_WITH_KNOTS('',3,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,(4,4),(0.,1.),.PIECEWISE_BEZIER_KNOTS.);";

#[test]
fn a_simple_curve_and_a_rational_complex_one_are_read() {
    let rational = "#6=( BOUNDED_CURVE() B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.)\n\
        B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,2.),.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM()\n\
        RATIONAL_B_SPLINE_CURVE((1.,0.5,1.)) REPRESENTATION_ITEM('') );\n#7=LINE('',#1,#8);\n/* a comment */";
    let imported = read(&file(&format!("{CUBIC}\n{rational}")), &limits()).unwrap();
    assert_eq!(imported.skipped, 1);
    assert_eq!(imported.curves.len(), 2);
    let cubic = &imported.curves[0];
    assert_eq!(cubic.source, "#5");
    assert_eq!(cubic.curve.convention(), KnotConvention::Multiplicities);
    assert_eq!(
        cubic.curve.knots(),
        &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
    );
    let conic = &imported.curves[1].curve;
    assert_eq!(conic.weights(), Some(&[1.0, 0.5, 1.0][..]));
    assert_eq!(conic.degree(), 2);
}

#[test]
fn written_curves_read_back_bit_for_bit() {
    let limits = CurveLimits::default();
    let points = [
        [0.1, 1.0 / 3.0, -2.0],
        [1.5, 2e-9, 7.0],
        [3.0, 2.0, 1e300],
        [4.0, 0.0, 0.0],
    ];
    let knots = [0.0, 0.0, 0.0, 0.1, 0.7, 0.7, 0.7];
    let spatial = Curve::new(2, &points, &knots, Some(&[1.0, 0.3, 2.0, 1.0]), &limits).unwrap();
    let planar_points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
    let planar = Curve::new(
        3,
        &planar_points,
        &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        None,
        &limits,
    )
    .unwrap();
    let text = write(&[spatial.clone(), planar.clone()], &[]);
    let back = read(&text, &FileLimits::default()).unwrap();
    assert_eq!(back.skipped, 0);
    assert_eq!(back.curves[0].curve.knots(), spatial.knots());
    assert_eq!(
        back.curves[0].curve.control_points(),
        spatial.control_points()
    );
    assert_eq!(back.curves[0].curve.weights(), spatial.weights());
    // 2D as z = 0.
    assert_eq!(
        back.curves[1].curve.control_points(),
        planar.control_points()
    );
    assert_eq!(
        back.curves[1].curve.dimension(),
        crate::spline::Dimension::Three
    );
}

#[test]
fn malformed_files_are_errors_that_name_the_line() {
    let whole = file(CUBIC);
    for cut in [10, 40, 100, whole.len() - 5, whole.len() - 20] {
        let error = read(&whole[..cut], &limits()).unwrap_err();
        assert!(
            matches!(error, FileError::Malformed { .. }),
            "{cut}: {error}"
        );
    }
    let broken = [
        "#1=CARTESIAN_POINT('',(0.,0.));\n#1=CARTESIAN_POINT('',(0.,0.));",
        "#5=B_SPLINE_CURVE_WITH_KNOTS('',3,(#1,#2,#3,#9),.U.,.F.,.F.,(4,4),(0.,1.),.U.);",
        "#5=B_SPLINE_CURVE_WITH_KNOTS('',3,(#1),.U.,.F.,.F.,(4,4),(0.,1.));",
        "#5=B_SPLINE_CURVE_WITH_KNOTS('',3.5,(#1),.U.,.F.,.F.,(4,4),(0.,1.),.U.);",
        "#5=LINE('',#1,#2)",
        "#5=LINE('',#1,#2;",
        "#5=LINE('',#1,1E);",
        "#5=LINE('',#1,'unclosed);",
        "#5=X(1e999);",
    ];
    for data in broken {
        let error = read(&file(data), &limits()).unwrap_err();
        assert!(
            matches!(error, FileError::Malformed { .. }),
            "{data}: {error}"
        );
    }
    let error = read(&file(&CUBIC.replace("(4,4)", "(4,5)")), &limits()).unwrap_err();
    assert!(matches!(error, FileError::InvalidCurve { .. }), "{error}");
}

#[test]
fn limits_are_checked() {
    let small = FileLimits {
        max_bytes: 50,
        ..limits()
    };
    assert!(matches!(
        read(&file(CUBIC), &small),
        Err(FileError::TooLarge { .. })
    ));
    let few = FileLimits {
        max_entities: 3,
        ..limits()
    };
    assert!(matches!(
        read(&file(CUBIC), &few),
        Err(FileError::TooManyEntities { max: 3 })
    ));
    let deep = format!("#1=X({}1{});", "(".repeat(40), ")".repeat(40));
    assert!(matches!(
        read(&file(&deep), &limits()),
        Err(FileError::TooDeep { .. })
    ));
    let typed_deep = format!("#1=X({}1{});", "A(".repeat(40), ")".repeat(40));
    assert!(matches!(
        read(&file(&typed_deep), &limits()),
        Err(FileError::TooDeep { .. })
    ));
}
