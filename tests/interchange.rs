//! The STEP and DXF readers on real files (tests/data/interop: two STEP files of public CAD
//! sample collections and a DXF file written by ezdxf; provenance in README.md there), and
//! their limits.
#![allow(clippy::unwrap_used)]

use knotshape::interchange::{FileError, FileLimits, dxf, step};

fn text(name: &str) -> String {
    std::fs::read_to_string(format!(
        "{}/tests/data/interop/{name}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

#[test]
fn every_b_spline_curve_of_real_step_files_is_read() {
    for (name, dimensions) in [("splinecage.stp", [2, 3]), ("screw.step", [2, 3])] {
        let file = text(name);
        let imported = step::read(&file, &FileLimits::default()).unwrap();
        // Each entity names B_SPLINE_CURVE_WITH_KNOTS once, simple or complex.
        let entities = file.matches("B_SPLINE_CURVE_WITH_KNOTS").count();
        assert_eq!(imported.curves.len(), entities, "{name}");
        assert!(imported.curves.len() > 30, "{name}");
        for found in &imported.curves {
            let number: u64 = found.source.strip_prefix('#').unwrap().parse().unwrap();
            // The source names an instance that is a B-spline curve.
            let definition = format!("#{number}=");
            let compact: String = file.split_whitespace().collect();
            let at = compact.find(&definition).unwrap();
            assert!(
                compact[at..at + 200].contains("B_SPLINE_CURVE"),
                "{name} {number}"
            );
            let d = found.curve.dimension().count();
            assert!(dimensions.contains(&d), "{name}: {d}");
        }
        assert!(
            imported.skipped > 0,
            "{name}: lines and circles are skipped"
        );
    }
}

#[test]
fn splines_of_an_ezdxf_file_are_read_and_others_counted() {
    let imported = dxf::read(&text("ezdxf_r2000.dxf"), &FileLimits::default()).unwrap();
    assert_eq!(imported.curves.len(), 2);
    // A spline by fit points only, a line and a circle.
    assert_eq!(imported.skipped, 3);
    let rational = &imported.curves[1].curve;
    assert_eq!(rational.weights(), Some(&[1.0, 0.5, 1.0][..]));
    assert!(!imported.curves[0].source.is_empty());
}

#[test]
fn truncated_real_files_are_errors_as_a_whole() {
    let step_text = text("screw.step");
    let dxf_text = text("ezdxf_r2000.dxf");
    for fraction in [0.1, 0.5, 0.9, 0.999] {
        let cut = |t: &str| {
            let mut at = (t.len() as f64 * fraction) as usize;
            while !t.is_char_boundary(at) {
                at -= 1;
            }
            t[..at].to_owned()
        };
        assert!(step::read(&cut(&step_text), &FileLimits::default()).is_err());
        assert!(dxf::read(&cut(&dxf_text), &FileLimits::default()).is_err());
    }
    let small = FileLimits {
        max_entities: 100,
        ..FileLimits::default()
    };
    assert!(matches!(
        step::read(&step_text, &small),
        Err(FileError::TooManyEntities { max: 100 })
    ));
}

/// The 32 B-spline surfaces of the real STEP files (4 in splinecage.stp, 28 rational complex
/// ones in as1-oc-214.stp, none in screw.step), each from a `B_SPLINE_SURFACE_WITH_KNOTS`
/// entity; written and read back to the same numbers and the same points.
#[test]
fn every_b_spline_surface_of_real_step_files_is_read_and_written_back() {
    let mut total = 0;
    for (name, count, rational) in [
        ("splinecage.stp", 4, 0),
        ("as1-oc-214.stp", 28, 28),
        ("screw.step", 0, 0),
    ] {
        let file = text(name);
        let imported = step::read(&file, &FileLimits::default()).unwrap();
        assert_eq!(imported.surfaces.len(), count, "{name}");
        assert_eq!(
            file.matches("B_SPLINE_SURFACE_WITH_KNOTS").count(),
            count,
            "{name}"
        );
        let compact: String = file.split_whitespace().collect();
        for found in &imported.surfaces {
            let at = compact.find(&format!("{}=", found.source)).unwrap();
            assert!(
                compact[at..at + 300].contains("B_SPLINE_SURFACE"),
                "{name} {}",
                found.source
            );
        }
        assert_eq!(
            imported
                .surfaces
                .iter()
                .filter(|s| s.surface.is_rational())
                .count(),
            rational,
            "{name}"
        );
        total += imported.surfaces.len();
        if count == 0 {
            continue;
        }
        let surfaces: Vec<_> = imported
            .surfaces
            .iter()
            .map(|s| s.surface.clone())
            .collect();
        let written = step::write(&[], &surfaces);
        let back = step::read(&written, &FileLimits::default()).unwrap();
        assert_eq!(back.surfaces.len(), count);
        assert_eq!(back.skipped, 0);
        for (original, again) in surfaces.iter().zip(&back.surfaces) {
            let again = &again.surface;
            assert_eq!(original.control_points(), again.control_points());
            assert_eq!(original.weights(), again.weights());
            assert_eq!(original.u().knots(), again.u().knots());
            assert_eq!(original.v().knots(), again.v().knots());
            let [(u0, u1), (v0, v1)] = original.domain();
            for (s, t) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.9, 1.0)] {
                let (u, v) = (u0 + s * (u1 - u0), v0 + t * (v1 - v0));
                assert_eq!(original.point(u, v), again.point(u, v));
            }
        }
    }
    assert_eq!(total, 32);
}

/// Broken surface entities are errors naming the entity or the line, never a panic.
#[test]
fn broken_surface_entities_are_errors() {
    let points = "#1=CARTESIAN_POINT('',(0.,0.,0.));#2=CARTESIAN_POINT('',(0.,1.,0.));\
        #3=CARTESIAN_POINT('',(1.,0.,0.));#4=CARTESIAN_POINT('',(1.,1.,1.));#9=LINE('',#1,#2);";
    let file = |entity: &str| {
        format!(
            "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nENDSEC;\nDATA;\n{points}\n{entity}\nENDSEC;\nEND-ISO-10303-21;\n"
        )
    };
    let good = "#5=B_SPLINE_SURFACE_WITH_KNOTS('',1,1,((#1,#2),(#3,#4)),.UNSPECIFIED.,.F.,.F.,.F.,(2,2),(2,2),(0.,1.),(0.,1.),.UNSPECIFIED.);";
    let imported = step::read(&file(good), &FileLimits::default()).unwrap();
    assert_eq!(imported.surfaces.len(), 1);
    assert_eq!(imported.skipped, 1, "the line");
    assert_eq!(
        imported.surfaces[0].surface.point(1.0, 1.0),
        [1.0, 1.0, 1.0]
    );
    for (entity, invalid) in [
        (good.replace("(2,2),(2,2)", "(2,3),(2,2)"), true),
        (good.replace("((#1,#2),(#3,#4))", "((#1,#2),(#3))"), true),
        (good.replace("#4)", "#9)"), false),
        (good.replace("#4)", "#8)"), false),
        (good.replace(",.UNSPECIFIED.);", ");"), false),
        (good.replace("'',1,1", "'',1.5,1"), false),
        (good.replace("((#1,#2),(#3,#4))", "(#1,#2,#3,#4)"), false),
        (
            "#5=(BOUNDED_SURFACE() B_SPLINE_SURFACE_WITH_KNOTS((2,2),(2,2),(0.,1.),(0.,1.),.U.) SURFACE());"
                .to_owned(),
            false,
        ),
        (
            "#5=(BOUNDED_SURFACE() B_SPLINE_SURFACE(1,1,((#1,#2),(#3,#4)),.U.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS((2,2),(2,2),(0.,1.),(0.,1.),.U.) RATIONAL_B_SPLINE_SURFACE(((1.,0.),(1.,1.))) SURFACE());"
                .to_owned(),
            true,
        ),
    ] {
        let error = step::read(&file(&entity), &FileLimits::default()).unwrap_err();
        if invalid {
            assert!(
                matches!(error, FileError::InvalidSurface { .. }),
                "{entity}: {error}"
            );
        } else {
            assert!(
                matches!(error, FileError::Malformed { .. }),
                "{entity}: {error}"
            );
        }
    }
}
