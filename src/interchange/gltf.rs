//! Binary glTF 2.0 (`.glb`, `model/gltf-binary`) of a triangle mesh: one scene, one node, one
//! mesh with one triangle primitive (`POSITION`, `NORMAL`, `indices`), so that a web front end
//! hands it straight to a renderer (three.js's `GLTFLoader`, Babylon, model-viewer).
//!
//! glTF stores 32-bit floats. The positions are written relative to the centre of the mesh's
//! bounding box, which is the node's `translation` (a JSON number, full double precision):
//! far from the origin the rounding of the positions is then that of the mesh's extent, at
//! most `2⁻²⁴` of half its diagonal per coordinate, not that of its distance from the origin.
//! The asset's `extras` carry the mesh's certified `max_error` and that rounding bound.
//!
//! Layout (glTF 2.0 §4.4): a 12-byte header (`glTF`, version 2, total length), a JSON chunk
//! padded with spaces and a BIN chunk padded with zeros to multiples of four bytes; the BIN
//! chunk holds the positions, the normals (both `VEC3` of `FLOAT`) and the indices (`SCALAR`
//! of `UNSIGNED_INT`), in that order.

use serde_json::json;

use crate::surface::Mesh;

/// The media type of binary glTF.
pub const GLTF_BINARY: &str = "model/gltf-binary";

/// `glTF` in little-endian.
const MAGIC: u32 = 0x4654_6C67;
/// `JSON`.
const JSON_CHUNK: u32 = 0x4E4F_534A;
/// `BIN\0`.
const BIN_CHUNK: u32 = 0x004E_4942;
/// `ARRAY_BUFFER` and `ELEMENT_ARRAY_BUFFER` (buffer view targets).
const ARRAY_BUFFER: u32 = 34_962;
const ELEMENT_ARRAY_BUFFER: u32 = 34_963;
/// `FLOAT` and `UNSIGNED_INT` (accessor component types).
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
/// `TRIANGLES` (primitive mode).
const TRIANGLES: u32 = 4;

/// The mesh as a binary glTF file (module docs).
pub fn to_glb(mesh: &Mesh) -> Vec<u8> {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for vertex in &mesh.vertices {
        for c in 0..3 {
            min[c] = min[c].min(vertex[c]);
            max[c] = max[c].max(vertex[c]);
        }
    }
    if mesh.vertices.is_empty() {
        (min, max) = ([0.0; 3], [0.0; 3]);
    }
    let centre: [f64; 3] = std::array::from_fn(|c| 0.5 * (min[c] + max[c]));
    let half_diagonal = 0.5
        * (0..3)
            .map(|c| (max[c] - min[c]).powi(2))
            .sum::<f64>()
            .sqrt();
    let mut bin: Vec<u8> = Vec::new();
    let mut relative_min = [f32::INFINITY; 3];
    let mut relative_max = [f32::NEG_INFINITY; 3];
    for vertex in &mesh.vertices {
        for c in 0..3 {
            let x = (vertex[c] - centre[c]) as f32;
            relative_min[c] = relative_min[c].min(x);
            relative_max[c] = relative_max[c].max(x);
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
    let positions_length = bin.len();
    for normal in &mesh.normals {
        for &c in normal {
            bin.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    let normals_length = bin.len() - positions_length;
    for triangle in &mesh.triangles {
        for &index in triangle {
            bin.extend_from_slice(&index.to_le_bytes());
        }
    }
    let indices_length = bin.len() - positions_length - normals_length;
    if mesh.vertices.is_empty() {
        (relative_min, relative_max) = ([0.0; 3], [0.0; 3]);
    }
    let count = mesh.vertices.len();
    let document = json!({
        "asset": {
            "version": "2.0",
            "generator": "knotshape",
            "extras": {
                "max_error": mesh.max_error,
                "position_rounding": half_diagonal * f64::from(f32::EPSILON),
            }
        },
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": centre}],
        "meshes": [{"primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1},
            "indices": 2,
            "mode": TRIANGLES
        }]}],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": positions_length, "target": ARRAY_BUFFER},
            {"buffer": 0, "byteOffset": positions_length, "byteLength": normals_length, "target": ARRAY_BUFFER},
            {"buffer": 0, "byteOffset": positions_length + normals_length, "byteLength": indices_length, "target": ELEMENT_ARRAY_BUFFER}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": FLOAT, "count": count, "type": "VEC3",
             "min": relative_min, "max": relative_max},
            {"bufferView": 1, "componentType": FLOAT, "count": count, "type": "VEC3"},
            {"bufferView": 2, "componentType": UNSIGNED_INT, "count": 3 * mesh.triangles.len(), "type": "SCALAR"}
        ]
    });
    let mut text = document.to_string().into_bytes();
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    for word in [MAGIC, 2, total as u32, text.len() as u32, JSON_CHUNK] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&text);
    for word in [bin.len() as u32, BIN_CHUNK] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&bin);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn word(bytes: &[u8], at: usize) -> u32 {
        u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
    }

    #[test]
    fn a_square_reads_back_from_its_chunks() {
        let mesh = Mesh {
            vertices: vec![
                [1000.0, 0.0, 0.0],
                [1001.0, 0.0, 0.0],
                [1001.0, 1.0, 0.5],
                [1000.0, 1.0, 0.5],
            ],
            parameters: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            normals: vec![[0.0, 0.0, 1.0]; 4],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            max_error: 0.0,
        };
        let glb = to_glb(&mesh);
        assert_eq!(word(&glb, 0), MAGIC);
        assert_eq!(word(&glb, 4), 2);
        assert_eq!(word(&glb, 8) as usize, glb.len());
        let json_length = word(&glb, 12) as usize;
        assert_eq!(word(&glb, 16), JSON_CHUNK);
        let document: serde_json::Value =
            serde_json::from_slice(&glb[20..20 + json_length]).unwrap();
        let bin_at = 20 + json_length;
        assert_eq!(word(&glb, bin_at + 4), BIN_CHUNK);
        let bin = &glb[bin_at + 8..];
        assert_eq!(
            document["nodes"][0]["translation"],
            json!([1000.5, 0.5, 0.25])
        );
        let float = |k: usize| f32::from_le_bytes(bin[4 * k..4 * k + 4].try_into().unwrap());
        // Vertex 2 relative to the centre: (0.5, 0.5, 0.25).
        assert_eq!([float(6), float(7), float(8)], [0.5, 0.5, 0.25]);
        let indices_at = document["bufferViews"][2]["byteOffset"].as_u64().unwrap() as usize;
        let index = |k: usize| word(bin, indices_at + 4 * k);
        assert_eq!((0..6).map(index).collect::<Vec<_>>(), [0, 1, 2, 0, 2, 3]);
        assert_eq!(document["accessors"][0]["max"], json!([0.5, 0.5, 0.25]));
        assert_eq!(glb.len() % 4, 0);
    }
}
