//! Wire types of `POST /v1/curves/import` and `POST /v1/curves/export` (STEP and DXF files).

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::curve::{CurveBody, WireCoordinates};
use crate::http::surface::SurfaceBody;

/// A curve file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("step"))]
pub enum FileFormat {
    /// STEP (ISO 10303-21 exchange structure): `B_SPLINE_CURVE_WITH_KNOTS`,
    /// `B_SPLINE_SURFACE_WITH_KNOTS` and their rational complex forms.
    Step,
    /// ASCII DXF: `SPLINE` entities.
    Dxf,
}

/// A STEP or DXF file whose B-spline curves are wanted.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "format": "dxf",
    "data": "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n5\n2A\n70\n8\n71\n2\n72\n6\n73\n3\n40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n40\n1\n10\n0\n20\n0\n30\n0\n10\n1\n20\n2\n30\n0\n10\n2\n20\n0\n30\n0\n0\nENDSEC\n0\nEOF\n"
}))]
pub struct ImportRequest {
    /// The file's format.
    pub format: FileFormat,
    /// The file's text (at most the configured `max_file_bytes`, 1 MiB by default; ASCII
    /// DXF). Malformed or truncated text is a 422 as a whole (no partial answer).
    pub data: String,
}

/// One B-spline curve of the file: a curve object (STEP: distinct knots with multiplicities
/// and 2D or 3D points as the file has them; DXF: the full knot vector, 3D points) and where
/// it came from.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[schema(example = json!({
    "degree": 2, "control_points": [[0, 0, 0], [1, 2, 0], [2, 0, 0]],
    "knots": [0, 0, 0, 1, 1, 1], "source": "2A"
}))]
pub struct ImportedCurveBody {
    /// The degree `p >= 1`.
    #[schema(minimum = 1)]
    pub degree: usize,
    /// The control points, 2D or 3D.
    #[schema(value_type = Vec<Vec<f64>>)]
    pub control_points: Vec<WireCoordinates>,
    /// The knots: distinct values with `multiplicities` (STEP) or the full vector (DXF).
    pub knots: Vec<f64>,
    /// How often each of `knots` repeats (STEP).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multiplicities: Option<Vec<usize>>,
    /// The weights of a rational curve.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
    /// The entity: `#N` (STEP instance name) or the DXF handle (`line L` for a DXF entity
    /// without a handle).
    pub source: String,
}

impl ImportedCurveBody {
    /// The curve object `curve` (never periodic: files give curves over their period) with
    /// its `source`. Its fields are spelled out rather than flattened from [`CurveBody`],
    /// whose schema is closed (`additionalProperties: false`) and so could not be extended.
    pub fn new(curve: CurveBody, source: String) -> Self {
        ImportedCurveBody {
            degree: curve.degree,
            control_points: curve.control_points,
            knots: curve.knots,
            multiplicities: curve.multiplicities,
            weights: curve.weights,
            source,
        }
    }
}

/// One B-spline surface of a STEP file: a surface object (distinct knots with
/// multiplicities in both directions, 3D points) and the entity it came from.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[schema(example = json!({
    "degree_u": 1, "degree_v": 1,
    "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
    "knots_u": [0, 1], "knots_v": [0, 1],
    "multiplicities_u": [2, 2], "multiplicities_v": [2, 2], "source": "#42"
}))]
pub struct ImportedSurfaceBody {
    /// Degree in `u`.
    #[schema(minimum = 1)]
    pub degree_u: usize,
    /// Degree in `v`.
    #[schema(minimum = 1)]
    pub degree_v: usize,
    /// `control_points[i][j]`, `i` along `u`, all 3D.
    #[schema(value_type = Vec<Vec<Vec<f64>>>)]
    pub control_points: Vec<Vec<WireCoordinates>>,
    /// The distinct knots in `u`.
    pub knots_u: Vec<f64>,
    /// The distinct knots in `v`.
    pub knots_v: Vec<f64>,
    /// How often each of `knots_u` repeats.
    pub multiplicities_u: Vec<usize>,
    /// How often each of `knots_v` repeats.
    pub multiplicities_v: Vec<usize>,
    /// The weights of a rational surface, `weights[i][j]` for `control_points[i][j]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<Vec<f64>>>,
    /// The entity: `#N` (STEP instance name).
    pub source: String,
}

impl ImportedSurfaceBody {
    /// The surface object `surface` (read from a file: multiplicities in both directions,
    /// never periodic) with its `source`; fields spelled out as for [`ImportedCurveBody`].
    pub fn new(surface: SurfaceBody, source: String) -> Self {
        ImportedSurfaceBody {
            degree_u: surface.degree_u,
            degree_v: surface.degree_v,
            control_points: surface.control_points,
            knots_u: surface.knots_u,
            knots_v: surface.knots_v,
            multiplicities_u: surface.multiplicities_u.unwrap_or_default(),
            multiplicities_v: surface.multiplicities_v.unwrap_or_default(),
            weights: surface.weights,
            source,
        }
    }
}

/// Every B-spline curve and surface of the file.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[schema(example = json!({
    "curves": [{"degree": 2, "control_points": [[0, 0, 0], [1, 2, 0], [2, 0, 0]],
                "knots": [0, 0, 0, 1, 1, 1], "source": "2A"}],
    "surfaces": [],
    "skipped": 0
}))]
pub struct ImportResponse {
    /// The file's B-spline curves in the order of the file: STEP `B_SPLINE_CURVE_WITH_KNOTS`
    /// (simple or complex, rational), DXF `SPLINE` with control points.
    pub curves: Vec<ImportedCurveBody>,
    /// The file's B-spline surfaces in the order of the file: STEP
    /// `B_SPLINE_SURFACE_WITH_KNOTS` (simple or complex, rational); none from DXF.
    pub surfaces: Vec<ImportedSurfaceBody>,
    /// The other curve and surface entities of the file, not read (STEP: `LINE`, `CIRCLE`,
    /// `TRIMMED_CURVE`, `PLANE`, `CYLINDRICAL_SURFACE`, B-spline forms without knots, …; DXF:
    /// `LINE`, `ARC`, `CIRCLE`, `ELLIPSE`, polylines, …, and splines given by fit points
    /// only).
    pub skipped: usize,
}

/// Curves (and, in STEP, surfaces) to write as a STEP or DXF file.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "format": "step",
    "curves": [{"degree": 3, "control_points": [[0, 0], [1, 2], [3, 2], [4, 0]],
                "knots": [0, 1], "multiplicities": [4, 4]}]
}))]
pub struct ExportRequest {
    /// The file's format.
    pub format: FileFormat,
    /// Up to `max_file_entities` curves (any knot form; periodic curves are written as the
    /// ordinary curve over their period, which neither format's periodic notions match).
    /// At least one curve or surface in all.
    #[serde(default)]
    pub curves: Vec<CurveBody>,
    /// Surfaces, STEP only (any knot form; a periodic direction written as the clamped
    /// surface over its period): each `B_SPLINE_SURFACE_WITH_KNOTS`, rational ones in the
    /// complex form, which Open CASCADE's `STEPControl_Reader` transfers to faces.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub surfaces: Vec<SurfaceBody>,
}
