//! Unit tests of the DXF reader and writer: round trips, group codes and broken files.

use super::*;
use crate::spline::CurveLimits;

fn spline(extra: &str) -> String {
    format!(
        "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n5\n2A\n100\nAcDbSpline\n70\n12\n71\n2\n72\n6\n73\n3\n74\n0\n\
         40\n0.0\n40\n0.0\n40\n0.0\n40\n1.0\n40\n1.0\n40\n1.0\n41\n1.0\n41\n0.5\n41\n1.0\n\
         10\n0.0\n20\n0.0\n30\n0.0\n10\n1.0\n20\n1.0\n30\n0.0\n10\n2.0\n20\n0.0\n30\n0.0\n{extra}\
         0\nLINE\n10\n0\n20\n0\n0\nSPLINE\n5\n2B\n71\n3\n74\n2\n11\n0\n21\n0\n11\n1\n21\n1\n0\nENDSEC\n0\nEOF\n"
    )
}

#[test]
fn splines_are_read_and_fit_point_splines_skipped() {
    let imported = read(&spline(""), &FileLimits::default()).unwrap();
    assert_eq!(imported.skipped, 2);
    assert_eq!(imported.curves.len(), 1);
    let curve = &imported.curves[0];
    assert_eq!(curve.source, "2A");
    assert_eq!(curve.curve.weights(), Some(&[1.0, 0.5, 1.0][..]));
    assert_eq!(curve.curve.knots(), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
}

/// What a reader that honours group 42 does with a knot (ezdxf's `round_knots`):
/// `round(k, -int(log10(tolerance)))`, the knot rounded to that many decimals and read
/// back (both correctly rounded, as Python's `round` and `float` are).
fn rounded_by_reader(knot: f64, tolerance: f64) -> f64 {
    let decimals = -(tolerance.log10() as i64);
    let decimals = usize::try_from(decimals).unwrap();
    format!("{knot:.decimals$}").parse().unwrap()
}

/// The group 42 value written for a curve with `knots`.
fn written_tolerance(knots: &[f64], points: usize, degree: usize) -> f64 {
    let points: Vec<[f64; 2]> = (0..points).map(|i| [i as f64, (i % 2) as f64]).collect();
    let curve = Curve::new(degree, &points, knots, None, &CurveLimits::default()).unwrap();
    let text = write(&[curve]);
    let mut lines = text.lines().map(str::trim);
    let mut tolerance = None;
    while let Some(code) = lines.next() {
        let value = lines.next().unwrap();
        if code == "42" {
            tolerance = Some(value.parse().unwrap());
        }
    }
    tolerance.unwrap()
}

#[test]
fn the_knot_tolerance_keeps_the_knots_as_written() {
    let cases: [(&[f64], usize, usize); 4] = [
        // Random interior knots, 15 to 17 significant digits.
        (
            &[
                0.0,
                0.0,
                0.0,
                0.0,
                0.179589123456789,
                0.6180339887498949,
                1.0,
                1.0,
                1.0,
                1.0,
            ],
            6,
            3,
        ),
        // Magnitudes from 1e-9 to 1e4, negative too.
        (
            &[
                -2.5e-7,
                -2.5e-7,
                3.3e-9,
                0.1,
                12345.678901234567,
                12346.0,
                12346.0,
            ],
            5,
            1,
        ),
        // Two knots 1e-12 apart: the tolerance stays below a tenth of the gap.
        (&[0.0, 0.0, 0.0, 0.5, 0.500000000001, 1.0, 1.0, 1.0], 5, 2),
        // Knots with few digits: ezdxf's own 1e-10 is enough.
        (&[0.0, 0.0, 0.25, 0.5, 1.0, 1.0], 4, 1),
    ];
    for (knots, points, degree) in cases {
        let tolerance = written_tolerance(knots, points, degree);
        assert!(tolerance <= 1e-10, "{tolerance:e}");
        let written = exportable_knots(
            &Curve::new(
                degree,
                &vec![[0.0, 0.0]; points],
                knots,
                None,
                &CurveLimits::default(),
            )
            .unwrap(),
        );
        for &k in &written {
            assert_eq!(rounded_by_reader(k, tolerance), k, "{k} at {tolerance:e}");
        }
        let gap = written
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|&g| g > 0.0)
            .fold(f64::INFINITY, f64::min);
        assert!(
            tolerance <= gap / 10.0 * (1.0 + 1e-12),
            "{tolerance:e} {gap:e}"
        );
    }
    assert_eq!(written_tolerance(cases[3].0, 4, 1), 1e-10);
    // The tolerance written before, 1e-7, rounded such knots.
    assert_ne!(
        rounded_by_reader(0.179589123456789, 1e-7),
        0.179589123456789
    );
    assert_eq!(rounded_by_reader(0.179589123456789, 1e-7), 0.1795891);
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
    let curve = Curve::new(2, &points, &knots, Some(&[1.0, 0.3, 2.0, 1.0]), &limits).unwrap();
    let back = read(&write(std::slice::from_ref(&curve)), &FileLimits::default()).unwrap();
    assert_eq!(back.curves[0].curve.knots(), curve.knots());
    assert_eq!(
        back.curves[0].curve.control_points(),
        curve.control_points()
    );
    assert_eq!(back.curves[0].curve.weights(), curve.weights());
}

#[test]
fn malformed_and_truncated_files_are_errors() {
    let whole = spline("");
    for cut in [5, 30, whole.len() / 2, whole.len() - 4] {
        assert!(
            read(&whole[..cut], &FileLimits::default()).is_err(),
            "{cut}"
        );
    }
    for bad in [
        whole.replace("72\n6", "72\n7"),
        whole.replace("40\n1.0\n41", "40\nx\n41"),
        whole.replace("71\n2\n", ""),
        whole.replace("41\n0.5\n", ""),
        whole
            .replace("10\n2.0", "20\n2.0")
            .replacen("10\n0.0\n20\n0.0\n30\n0.0\n", "20\n0.0\n", 1),
        whole.replace("ENDSEC\n0\nEOF", "EOF"),
    ] {
        assert!(read(&bad, &FileLimits::default()).is_err(), "{bad}");
    }
    let few = FileLimits {
        max_entities: 2,
        ..FileLimits::default()
    };
    assert!(matches!(
        read(&whole, &few),
        Err(FileError::TooManyEntities { .. })
    ));
}
