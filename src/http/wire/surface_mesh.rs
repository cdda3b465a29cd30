//! Wire types of `POST /v1/surfaces/tessellate`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use crate::http::surface::SurfaceBody;
use crate::surface::Mesh;

/// How the mesh is answered.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, Serialize, ToSchema)]
#[serde(rename_all = "lowercase")]
#[schema(example = json!("gltf"))]
pub enum MeshFormat {
    /// `application/json`: the fields of `TessellateResponse`.
    #[default]
    Json,
    /// `model/gltf-binary`: the same mesh as binary glTF 2.0 (positions and normals as 32-bit
    /// floats, positions relative to the node's `translation`, the bounding box's centre;
    /// `asset.extras` holds `max_error` and the float rounding bound `position_rounding`).
    Gltf,
}

/// A surface to mesh within a tolerance.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "surface": {"degree_u": 1, "degree_v": 1,
                "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
                "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1]},
    "tolerance": 0.1
}))]
pub struct TessellateRequest {
    /// The surface (continuous: no interior knot of multiplicity `degree + 1`).
    pub surface: SurfaceBody,
    /// A distance `τ > 0`, at least `1e-9` times the largest control-point coordinate
    /// magnitude: every point of the surface lies within `τ` of the mesh and every point of
    /// the mesh within `τ` of the surface (certified, module docs of the method).
    #[schema(exclusive_minimum = 0, example = 0.1)]
    pub tolerance: f64,
    /// `"json"` (default) or `"gltf"` (binary glTF, `model/gltf-binary`).
    #[serde(default)]
    pub format: MeshFormat,
}

/// The mesh.
#[derive(Debug, Clone, Deserialize, Serialize, ToSchema)]
#[schema(example = json!({
    "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 1], [0, 1, 0]],
    "parameters": [[0, 0], [1, 0], [1, 1], [0, 1]],
    "normals": [[0, 0, 1], [0, -0.707, 0.707], [-0.577, -0.577, 0.577], [-0.707, 0, 0.707]],
    "triangles": [[0, 1, 3], [1, 2, 3]],
    "max_error": 0.0625
}))]
pub struct TessellateResponse {
    /// The vertices `S(u, v)`.
    pub vertices: Vec<[f64; 3]>,
    /// `[u, v]` of each vertex.
    pub parameters: Vec<[f64; 2]>,
    /// The unit normal `S_u × S_v / |S_u × S_v|` at each vertex (its limit at a degenerate
    /// point, as `/v1/surfaces/evaluate` gives it; where the surface has none, the normalised
    /// sum of the vertex's triangles' normals). At a knot the normal of the patch on the right.
    pub normals: Vec<[f64; 3]>,
    /// Vertex index triples, counter-clockwise in `(u, v)`, so counter-clockwise seen from the
    /// side the normals point to (where the mesh resolves the surface: a triangle not much
    /// larger than `max_error` may turn any way and still be within it). Neighbouring
    /// triangles share whole edges: no cracks inside the surface.
    pub triangles: Vec<[u32; 3]>,
    /// The certified bound the mesh meets (`<= tolerance`): the Hausdorff distance between
    /// the mesh and the surface is at most this.
    pub max_error: f64,
}

impl TessellateResponse {
    /// The wire form of a core mesh.
    pub fn from_core(mesh: Mesh) -> Self {
        TessellateResponse {
            vertices: mesh.vertices,
            parameters: mesh.parameters,
            normals: mesh.normals,
            triangles: mesh.triangles,
            max_error: mesh.max_error,
        }
    }
}
