//! Curve (and surface) files: STEP (ISO 10303-21) and DXF text in, core curves out, and the
//! reverse; meshes out as binary glTF. Pure:
//! no HTTP types; every loop over the file's content is bounded by [`FileLimits`].
//!
//! Untrusted input: the text's size is checked before anything is read, the number of entities
//! and the nesting of lists as they are read (before any geometry is built), so the work and
//! memory of a read are linear in the (bounded) size of the text. A file that is malformed
//! anywhere is an error as a whole: no partial answer.

pub mod dxf;
pub mod gltf;
mod numbers;
pub mod step;

use crate::spline::{Curve, CurveError, CurveLimits};
use crate::surface::{Surface, SurfaceError, SurfaceLimits};

/// Limits applied to a file read (the service makes them configurable).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FileLimits {
    /// Largest accepted text, in bytes.
    pub max_bytes: usize,
    /// Largest number of entities (STEP instances, DXF entities) in a file.
    pub max_entities: usize,
    /// The limits each curve of the file must respect.
    pub curve_limits: CurveLimits,
    /// The limits each surface of the file must respect.
    pub surface_limits: SurfaceLimits,
}

impl Default for FileLimits {
    fn default() -> Self {
        FileLimits {
            max_bytes: 1024 * 1024,
            max_entities: 100_000,
            curve_limits: CurveLimits::default(),
            surface_limits: SurfaceLimits::default(),
        }
    }
}

/// Deepest nesting of lists (and typed values) accepted in a STEP file: the curves' entities
/// need 2, real files rarely more than 4.
pub const MAX_NESTING: usize = 32;

/// One B-spline curve of a file and where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportedCurve {
    /// The curve (in the file's knot form: STEP's distinct knots with multiplicities, DXF's
    /// full vector).
    pub curve: Curve,
    /// The entity: `#N` for STEP, the handle for DXF (`line L` when an entity has none).
    pub source: String,
}

/// One B-spline surface of a file and where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportedSurface {
    /// The surface (STEP's distinct knots with multiplicities in both directions).
    pub surface: Surface,
    /// The entity: `#N`.
    pub source: String,
}

/// Everything a read finds.
#[derive(Debug, Clone, PartialEq)]
pub struct Imported {
    /// The file's B-spline curves, in the order of the file.
    pub curves: Vec<ImportedCurve>,
    /// The file's B-spline surfaces, in the order of the file (STEP only).
    pub surfaces: Vec<ImportedSurface>,
    /// The other curve and surface entities (and DXF splines given by fit points only).
    pub skipped: usize,
}

/// Why a file cannot be read. Line numbers count from 1.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FileError {
    /// The text is larger than [`FileLimits::max_bytes`].
    #[error("the file has {bytes} bytes, above the limit {max}")]
    TooLarge { bytes: usize, max: usize },
    /// The file has more entities than [`FileLimits::max_entities`].
    #[error("the file has more than {max} entities")]
    TooManyEntities { max: usize },
    /// Lists nest deeper than [`MAX_NESTING`].
    #[error("line {line}: lists nest deeper than {MAX_NESTING}")]
    TooDeep { line: usize },
    /// The text breaks the format's syntax or structure (truncated files included).
    #[error("line {line}: {message}")]
    Malformed { line: usize, message: String },
    /// A B-spline entity's data break a rule of curves.
    #[error("{entity}: {error}")]
    InvalidCurve { entity: String, error: CurveError },
    /// A B-spline surface entity's data break a rule of surfaces.
    #[error("{entity}: {error}")]
    InvalidSurface { entity: String, error: SurfaceError },
}

/// The [`FileError::Malformed`] at `line`.
fn malformed(line: usize, message: impl Into<String>) -> FileError {
    FileError::Malformed {
        line,
        message: message.into(),
    }
}

/// Checks the size limit before anything is read.
fn check_size(text: &str, limits: &FileLimits) -> Result<(), FileError> {
    if text.len() > limits.max_bytes {
        return Err(FileError::TooLarge {
            bytes: text.len(),
            max: limits.max_bytes,
        });
    }
    Ok(())
}

/// The curve a file holds for `curve`: itself, or for a periodic curve (which neither STEP nor
/// DXF can say the way Open CASCADE does) the clamped curve over its period.
fn exportable_curve(curve: &Curve) -> Curve {
    if curve.is_periodic() {
        curve.clamped()
    } else {
        curve.clone()
    }
}

/// The surface a file holds for `surface`: itself, or with each periodic direction cut open
/// to the clamped surface over its period (as [`exportable_curve`] does for the curves
/// through its columns or rows).
fn exportable_surface(surface: &Surface) -> Surface {
    let mut out = surface.clone();
    if out.u().is_periodic() {
        let columns: Vec<Curve> = (0..out.v().count())
            .map(|j| out.column(j).clamped())
            .collect();
        out = out.with_columns(&columns);
    }
    if out.v().is_periodic() {
        let rows: Vec<Curve> = (0..out.u().count()).map(|i| out.row(i).clamped()).collect();
        out = out.with_rows(&rows);
    }
    out
}

/// A curve's full knot vector made acceptable to readers that allow at most `degree + 1`
/// equal values at an end (STEP, Open CASCADE, DXF): an end run of `degree + 2` (the full
/// convention allows it; the outermost value has no effect on the curve) gets its outermost
/// value moved one domain length out.
fn exportable_knots(curve: &Curve) -> Vec<f64> {
    let mut knots = curve.knots().to_vec();
    let p = curve.degree();
    let (lo, hi) = curve.domain();
    let last = knots.len() - 1;
    if knots[..=p + 1].iter().all(|&u| u == knots[0]) {
        knots[0] -= hi - lo;
    }
    if knots[last - p - 1..].iter().all(|&u| u == knots[last]) {
        knots[last] += hi - lo;
    }
    knots
}
