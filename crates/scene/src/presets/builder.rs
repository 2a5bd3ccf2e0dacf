//! A minimal glTF 2.0 writer: meshes, materials, PNG textures, nodes, one camera, one scene.
//! Used by the bundled presets and by tests that need small (or deliberately broken) files.
//! Output is deterministic: JSON keys are sorted and the binary layout follows call order.

use serde_json::{Value, json};

/// Vertex data of one mesh (one primitive, TRIANGLES).
#[derive(Clone, Debug, Default)]
pub struct MeshData {
    pub positions: Vec<[f32; 3]>,
    pub normals: Option<Vec<[f32; 3]>>,
    pub uvs: Option<Vec<[f32; 2]>>,
    /// `None`: non-indexed (every three vertices form a triangle).
    pub indices: Option<Vec<u32>>,
}

/// Builds one glTF document with a single binary buffer.
#[derive(Clone, Debug, Default)]
pub struct GltfBuilder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    materials: Vec<Value>,
    textures: Vec<Value>,
    images: Vec<Value>,
    samplers: Vec<Value>,
    cameras: Vec<Value>,
    nodes: Vec<Value>,
    roots: Vec<usize>,
    scene_extras: Option<Value>,
    extensions: Vec<String>,
}

impl GltfBuilder {
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends raw bytes (4-byte aligned) as a buffer view; returns the view index.
    pub fn add_view(&mut self, bytes: &[u8]) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.views.push(json!({
            "buffer": 0, "byteOffset": offset, "byteLength": bytes.len()
        }));
        self.views.len() - 1
    }

    /// Appends an accessor over a new view; returns the accessor index.
    pub fn add_accessor(
        &mut self,
        bytes: &[u8],
        count: usize,
        component_type: u32,
        ty: &str,
        min_max: Option<(Vec<f32>, Vec<f32>)>,
    ) -> usize {
        let view = self.add_view(bytes);
        let mut a = json!({
            "bufferView": view, "componentType": component_type, "count": count, "type": ty
        });
        if let Some((min, max)) = min_max {
            a["min"] = json!(min);
            a["max"] = json!(max);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// Adds a mesh with one triangle primitive; returns the mesh index.
    pub fn add_mesh(&mut self, name: &str, mesh: &MeshData, material: Option<usize>) -> usize {
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in &mesh.positions {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let pos = self.add_accessor(
            bytemuck::cast_slice(&mesh.positions),
            mesh.positions.len(),
            5126,
            "VEC3",
            Some((min.to_vec(), max.to_vec())),
        );
        let mut attributes = json!({ "POSITION": pos });
        if let Some(n) = &mesh.normals {
            attributes["NORMAL"] =
                json!(self.add_accessor(bytemuck::cast_slice(n), n.len(), 5126, "VEC3", None));
        }
        if let Some(uv) = &mesh.uvs {
            attributes["TEXCOORD_0"] =
                json!(self.add_accessor(bytemuck::cast_slice(uv), uv.len(), 5126, "VEC2", None));
        }
        let mut prim = json!({ "attributes": attributes, "mode": 4 });
        if let Some(idx) = &mesh.indices {
            prim["indices"] = json!(self.add_accessor(
                bytemuck::cast_slice(idx),
                idx.len(),
                5125,
                "SCALAR",
                None
            ));
        }
        if let Some(m) = material {
            prim["material"] = json!(m);
        }
        self.meshes
            .push(json!({ "name": name, "primitives": [prim] }));
        self.meshes.len() - 1
    }

    /// Adds a raw material object; returns its index.
    pub fn add_material(&mut self, material: Value) -> usize {
        for ext in ["KHR_materials_emissive_strength", "KHR_materials_specular"] {
            if material.pointer(&format!("/extensions/{ext}")).is_some() {
                self.use_extension(ext);
            }
        }
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Embeds PNG bytes as an image in the binary buffer and adds a texture with the given
    /// sampler (raw glTF sampler object, e.g. `{"wrapS": 10497}`); returns the texture index.
    pub fn add_png_texture(&mut self, name: &str, png: &[u8], sampler: Value) -> usize {
        let view = self.add_view(png);
        self.images
            .push(json!({ "name": name, "bufferView": view, "mimeType": "image/png" }));
        self.samplers.push(sampler);
        self.textures.push(json!({
            "source": self.images.len() - 1, "sampler": self.samplers.len() - 1
        }));
        self.textures.len() - 1
    }

    /// Adds a perspective camera; returns its index.
    pub fn add_camera(&mut self, yfov: f64, aspect_ratio: f64) -> usize {
        self.cameras.push(json!({
            "type": "perspective",
            "perspective": { "yfov": yfov, "aspectRatio": aspect_ratio, "znear": 0.001, "zfar": 1000.0 }
        }));
        self.cameras.len() - 1
    }

    /// Adds a raw node object (`mesh`, `camera`, `children`, TRS or `matrix`); returns its index.
    pub fn add_node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// Makes a node a root of the scene.
    pub fn add_root(&mut self, node: usize) {
        self.roots.push(node);
    }

    pub fn set_scene_extras(&mut self, extras: Value) {
        self.scene_extras = Some(extras);
    }

    pub fn use_extension(&mut self, name: &str) {
        if !self.extensions.iter().any(|e| e == name) {
            self.extensions.push(name.to_string());
        }
    }

    /// The binary buffer so far.
    pub fn bin(&self) -> &[u8] {
        &self.bin
    }

    /// The glTF JSON with buffer 0 at `buffer_uri` (`None` for the GLB binary chunk).
    /// Tests may edit the returned value to produce broken files.
    pub fn json(&self, buffer_uri: Option<String>) -> Value {
        let mut buffer = json!({ "byteLength": self.bin.len() });
        if let Some(uri) = buffer_uri {
            buffer["uri"] = json!(uri);
        }
        let mut scene = json!({ "nodes": self.roots });
        if let Some(e) = &self.scene_extras {
            scene["extras"] = e.clone();
        }
        let mut doc = json!({
            "asset": { "version": "2.0", "generator": "blueshift-scene" },
            "scene": 0,
            "scenes": [scene],
            "nodes": self.nodes,
            "meshes": self.meshes,
            "accessors": self.accessors,
            "bufferViews": self.views,
            "buffers": [buffer],
        });
        for (key, list) in [
            ("materials", &self.materials),
            ("textures", &self.textures),
            ("images", &self.images),
            ("samplers", &self.samplers),
            ("cameras", &self.cameras),
        ] {
            if !list.is_empty() {
                doc[key] = json!(list);
            }
        }
        if !self.extensions.is_empty() {
            doc["extensionsUsed"] = json!(self.extensions);
        }
        doc
    }

    /// A self-contained `.gltf`: JSON with the buffer as a base64 data URI.
    pub fn to_gltf_embedded(&self) -> Vec<u8> {
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            super::base64::encode(&self.bin)
        );
        to_pretty(&self.json(Some(uri)))
    }

    /// A `.gltf` referencing an external `.bin` named `bin_name`: `(json, bin)`.
    pub fn to_gltf_external(&self, bin_name: &str) -> (Vec<u8>, Vec<u8>) {
        (
            to_pretty(&self.json(Some(bin_name.to_string()))),
            self.bin.clone(),
        )
    }

    /// A binary `.glb`.
    pub fn to_glb(&self) -> Vec<u8> {
        glb(&self.json(None), &self.bin)
    }
}

fn to_pretty(v: &Value) -> Vec<u8> {
    let mut s = serde_json::to_string_pretty(v)
        .unwrap_or_default()
        .into_bytes();
    s.push(b'\n');
    s
}

/// Packs JSON and a binary chunk into a GLB container.
pub fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).unwrap_or_default();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while b.len() % 4 != 0 {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + if b.is_empty() { 0 } else { 8 + b.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    if !b.is_empty() {
        out.extend_from_slice(&(b.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&b);
    }
    out
}
