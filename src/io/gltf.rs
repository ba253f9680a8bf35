//! glTF 2.0: convex solids as one scene (a rough with its planned cuts inside), written as a
//! single `.gltf` JSON file with its buffer embedded (base64 data URI). Written by hand with
//! `serde_json` (the glTF crates would add a dependency for a few dozen lines of JSON).
//!
//! Each solid is one mesh of flat triangles (each facet a fan, its vertices repeated so each
//! facet has its own normal), positions in **metres** as glTF asks (the solids' millimetres ×
//! 0.001), with a material of its own colour; a colour whose alpha is below 1 is blended (the
//! rough drawn see-through around its cuts). Every primitive is `float32` positions and
//! normals and `uint32` indices, each accessor with its bounds as the format requires.

use crate::geometry::Polyhedron;
use base64::Engine;
use serde_json::{json, Value};

/// One solid of a scene: its name, the solid (mm), and its colour (linear RGBA, 0–1).
pub struct GltfObject<'a> {
    /// The node's and mesh's name.
    pub name: &'a str,
    /// The solid, in millimetres.
    pub solid: &'a Polyhedron,
    /// Base colour, linear RGBA 0–1 (alpha below 1: blended).
    pub rgba: [f32; 4],
}

/// Metres per millimetre.
const METRES: f64 = 1e-3;

/// The scene as glTF 2.0 JSON text.
pub fn write_gltf(objects: &[GltfObject<'_>], generator: &str) -> String {
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    let mut materials = Vec::new();
    let mut nodes = Vec::new();
    for (k, o) in objects.iter().enumerate() {
        let mut pos: Vec<[f32; 3]> = Vec::new();
        let mut nrm: Vec<[f32; 3]> = Vec::new();
        let mut idx: Vec<u32> = Vec::new();
        for (i, f) in o.solid.facets().iter().enumerate() {
            let poly = o.solid.facet_polygon(i);
            let base = pos.len() as u32;
            let n = f.plane.normal.as_vec3().to_array();
            for p in &poly {
                pos.push((*p * METRES).as_vec3().to_array());
                nrm.push(n);
            }
            for t in 1..poly.len().saturating_sub(1) as u32 {
                idx.extend([base, base + t, base + t + 1]);
            }
        }
        let (lo, hi) = pos
            .iter()
            .fold(([f32::MAX; 3], [f32::MIN; 3]), |(mut lo, mut hi), p| {
                for c in 0..3 {
                    lo[c] = lo[c].min(p[c]);
                    hi[c] = hi[c].max(p[c]);
                }
                (lo, hi)
            });
        let mut view = |bytes: Vec<u8>, target: u32| {
            while !bin.len().is_multiple_of(4) {
                bin.push(0);
            }
            views.push(json!({
                "buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len(), "target": target
            }));
            bin.extend(bytes);
            views.len() - 1
        };
        let floats = |v: &[[f32; 3]]| v.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        let vp = view(floats(&pos), 34962);
        let vn = view(floats(&nrm), 34962);
        let vi = view(idx.iter().flat_map(|x| x.to_le_bytes()).collect(), 34963);
        let a0 = accessors.len();
        accessors.push(json!({
            "bufferView": vp, "componentType": 5126, "count": pos.len(), "type": "VEC3",
            "min": lo, "max": hi
        }));
        accessors.push(json!({
            "bufferView": vn, "componentType": 5126, "count": nrm.len(), "type": "VEC3"
        }));
        accessors.push(json!({
            "bufferView": vi, "componentType": 5125, "count": idx.len(), "type": "SCALAR"
        }));
        let blend = o.rgba[3] < 1.0;
        materials.push(json!({
            "name": o.name,
            "pbrMetallicRoughness": {
                "baseColorFactor": o.rgba, "metallicFactor": 0.0, "roughnessFactor": 0.2
            },
            "alphaMode": if blend { "BLEND" } else { "OPAQUE" },
            "doubleSided": blend
        }));
        meshes.push(json!({
            "name": o.name,
            "primitives": [{
                "attributes": { "POSITION": a0, "NORMAL": a0 + 1 },
                "indices": a0 + 2, "material": k, "mode": 4
            }]
        }));
        nodes.push(json!({ "name": o.name, "mesh": k }));
    }
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bin)
    );
    let doc: Value = json!({
        "asset": { "version": "2.0", "generator": generator },
        "scene": 0,
        "scenes": [{ "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{ "byteLength": bin.len(), "uri": uri }]
    });
    let mut text = serde_json::to_string_pretty(&doc).unwrap_or_default();
    text.push('\n');
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{DVec3, FacetPlane};

    fn cube(half: f64) -> Polyhedron {
        let planes: Vec<FacetPlane> = [DVec3::X, DVec3::Y, DVec3::Z]
            .iter()
            .flat_map(|n| [*n, -*n])
            .enumerate()
            .map(|(i, n)| FacetPlane::new(n, half, format!("f{i}"), "t"))
            .collect();
        Polyhedron::from_planes(&planes).unwrap()
    }

    /// Read the scene back: the buffer decodes to the solids' triangles (in metres), every
    /// accessor fits its view, the bounds are the solids', and the triangles enclose the
    /// solids' volumes (divergence theorem over the decoded triangles).
    #[test]
    fn the_scene_reads_back_to_its_solids() {
        let (big, small) = (cube(2.0), cube(0.5));
        let text = write_gltf(
            &[
                GltfObject {
                    name: "rough",
                    solid: &big,
                    rgba: [0.8, 0.8, 0.9, 0.3],
                },
                GltfObject {
                    name: "cut",
                    solid: &small,
                    rgba: [1.0, 1.0, 1.0, 1.0],
                },
            ],
            "test",
        );
        let doc: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(doc["asset"]["version"], "2.0");
        let uri = doc["buffers"][0]["uri"].as_str().unwrap();
        let bin = base64::engine::general_purpose::STANDARD
            .decode(uri.split_once(',').unwrap().1)
            .unwrap();
        assert_eq!(
            bin.len() as u64,
            doc["buffers"][0]["byteLength"].as_u64().unwrap()
        );
        let view = |a: &Value| -> Vec<u8> {
            let v = &doc["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
            let off = v["byteOffset"].as_u64().unwrap() as usize;
            let len = v["byteLength"].as_u64().unwrap() as usize;
            assert!(off.is_multiple_of(4));
            bin[off..off + len].to_vec()
        };
        for (m, (solid, half)) in [(&big, 2.0), (&small, 0.5)].iter().enumerate() {
            let prim = &doc["meshes"][m]["primitives"][0];
            let acc =
                |key: &str| &doc["accessors"][prim["attributes"][key].as_u64().unwrap() as usize];
            let pos_acc = acc("POSITION");
            let pos: Vec<f32> = view(pos_acc)
                .chunks(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect();
            assert_eq!(pos.len() as u64, 3 * pos_acc["count"].as_u64().unwrap());
            let idx_acc = &doc["accessors"][prim["indices"].as_u64().unwrap() as usize];
            let idx: Vec<u32> = view(idx_acc)
                .chunks(4)
                .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
                .collect();
            assert_eq!(idx.len(), 6 * 2 * 3);
            let p = |i: u32| {
                let i = i as usize * 3;
                DVec3::new(pos[i] as f64, pos[i + 1] as f64, pos[i + 2] as f64)
            };
            let volume: f64 = idx
                .chunks(3)
                .map(|t| p(t[0]).dot(p(t[1]).cross(p(t[2]))) / 6.0)
                .sum();
            let expected = solid.volume() * 1e-9;
            assert!(
                (volume - expected).abs() < 1e-6 * expected,
                "{volume} vs {expected}"
            );
            let max = pos_acc["max"][0].as_f64().unwrap();
            assert!((max - half * 1e-3).abs() < 1e-9);
        }
        assert_eq!(doc["materials"][0]["alphaMode"], "BLEND");
        assert_eq!(doc["materials"][1]["alphaMode"], "OPAQUE");
    }
}
