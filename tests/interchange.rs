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
