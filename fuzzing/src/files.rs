//! The checks shared by the fuzz targets `step_import`, `step_surfaces` and `dxf_import`
//! (`fuzz/`) and the corpus replay test (`tests/fuzz_corpus.rs`): any bytes, as text, through a
//! file reader must give curves (and surfaces) or an error, never a panic; the curves and
//! surfaces read must write and read back to the same control points, weights and domains.

use knotshape::interchange::{FileLimits, Imported, dxf, step};
use knotshape::spline::Curve;
use knotshape::surface::Surface;

/// A reader or a writer of one format.
type Reader = fn(&str, &FileLimits) -> Result<Imported, knotshape::interchange::FileError>;
type Writer = fn(&[Curve]) -> String;

/// Reads `input` as a STEP file and checks the round trip of what it holds.
pub fn check_step(input: &[u8]) -> Result<(), String> {
    check(input, step::read, |curves| step::write(curves, &[]))
}

/// Reads `input` as a STEP file and checks the round trip of the surfaces it holds: written
/// (with no curves) and read back, each surface has the same degrees, domain, control points
/// and weights (a periodic direction comes back clamped over its period, which files never
/// hold: what is read is never periodic).
pub fn check_step_surfaces(input: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(input);
    let limits = FileLimits {
        max_entities: 2_000,
        ..FileLimits::default()
    };
    let Ok(imported) = step::read(&text, &limits) else {
        return Ok(());
    };
    let surfaces: Vec<Surface> = imported
        .surfaces
        .iter()
        .map(|s| s.surface.clone())
        .collect();
    if surfaces.is_empty() {
        return Ok(());
    }
    let written = step::write(&[], &surfaces);
    let back = step::read(&written, &FileLimits::default())
        .map_err(|error| format!("a written file does not read back: {error}\n{written}"))?;
    if back.surfaces.len() != surfaces.len() || !back.curves.is_empty() || back.skipped != 0 {
        return Err(format!(
            "{} surfaces written, {} surfaces and {} curves read back ({} skipped)",
            surfaces.len(),
            back.surfaces.len(),
            back.curves.len(),
            back.skipped
        ));
    }
    for (index, (original, again)) in surfaces.iter().zip(&back.surfaces).enumerate() {
        let again = &again.surface;
        let same = original.u().degree() == again.u().degree()
            && original.v().degree() == again.v().degree()
            && original.domain() == again.domain()
            && original.control_points() == again.control_points()
            && original.weights() == again.weights();
        if !same {
            return Err(format!(
                "surface {index} changed in the round trip: {original:?} → {again:?}"
            ));
        }
    }
    Ok(())
}

/// Reads `input` as a DXF file and checks the round trip of what it holds.
pub fn check_dxf(input: &[u8]) -> Result<(), String> {
    check(input, dxf::read, dxf::write)
}

fn check(input: &[u8], read: Reader, write: Writer) -> Result<(), String> {
    let text = String::from_utf8_lossy(input);
    let limits = FileLimits {
        max_entities: 2_000,
        ..FileLimits::default()
    };
    let Ok(imported) = read(&text, &limits) else {
        return Ok(());
    };
    let curves: Vec<Curve> = imported.curves.iter().map(|c| c.curve.clone()).collect();
    if curves.is_empty() {
        return Ok(());
    }
    let written = write(&curves);
    let back = read(&written, &FileLimits::default())
        .map_err(|error| format!("a written file does not read back: {error}\n{written}"))?;
    if back.curves.len() != curves.len() || back.skipped != 0 {
        return Err(format!(
            "{} curves written, {} read back ({} skipped)",
            curves.len(),
            back.curves.len(),
            back.skipped
        ));
    }
    for (index, (original, again)) in curves.iter().zip(&back.curves).enumerate() {
        let again = &again.curve;
        let same = original.degree() == again.degree()
            && original.control_points() == again.control_points()
            && original.weights() == again.weights()
            && original.domain() == again.domain();
        if !same {
            return Err(format!(
                "curve {index} changed in the round trip: {original:?} → {again:?}"
            ));
        }
    }
    Ok(())
}
