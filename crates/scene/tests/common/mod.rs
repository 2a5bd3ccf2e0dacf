//! Helpers shared by the integration tests.
#![allow(dead_code)]

use blueshift_scene::presets::{GltfBuilder, MeshData};
use blueshift_scene::{LoadBudget, LoadOptions, Ray, Scene, SceneError};
use glam::Vec3;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// xorshift64*: deterministic, dependency-free random numbers.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    /// Uniform in [0, 1).
    pub fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }
    pub fn vec3(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
    pub fn unit_vector(&mut self) -> Vec3 {
        loop {
            let v = self.vec3(-1.0, 1.0);
            let l = v.length();
            if l > 1e-3 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

/// Random triangles in a cube of side `extent`, each at most `size` across.
pub fn triangle_soup(n: usize, extent: f32, size: f32, seed: u64) -> Vec<[Vec3; 3]> {
    let mut rng = Rng::new(seed);
    (0..n)
        .map(|_| {
            let c = rng.vec3(-extent * 0.5, extent * 0.5);
            [
                c + rng.vec3(-size, size),
                c + rng.vec3(-size, size),
                c + rng.vec3(-size, size),
            ]
        })
        .collect()
}

/// Random rays: origins in a box around `bounds`, mixed directions (some axis-aligned), some
/// aimed at random points inside, with random finite `tmax` on a quarter of them.
pub fn random_rays(n: usize, lo: Vec3, hi: Vec3, seed: u64) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    let size = hi - lo;
    let pad = size * 0.25;
    (0..n)
        .map(|k| {
            let o = lo - pad + (size + 2.0 * pad) * Vec3::new(rng.f32(), rng.f32(), rng.f32());
            let dir = match k % 4 {
                0 => rng.unit_vector(),
                1 => {
                    let target = lo + size * Vec3::new(rng.f32(), rng.f32(), rng.f32());
                    (target - o).normalize_or(Vec3::X)
                }
                2 => {
                    // Axis-aligned directions exercise the zero-component slab case.
                    let axes = [
                        Vec3::X,
                        Vec3::NEG_X,
                        Vec3::Y,
                        Vec3::NEG_Y,
                        Vec3::Z,
                        Vec3::NEG_Z,
                    ];
                    axes[(rng.next_u64() % 6) as usize]
                }
                _ => {
                    let target = lo + size * Vec3::new(rng.f32(), rng.f32(), rng.f32());
                    (target - o) * rng.range(0.1, 3.0) // not unit length
                }
            };
            let tmax = if k % 4 == 3 {
                rng.range(0.1, 2.0)
            } else {
                f32::MAX
            };
            Ray::new(o, dir, if k % 8 == 5 { 0.05 } else { 0.0 }, tmax)
        })
        .collect()
}

/// A unit quad (two triangles) in the z = 0 plane, optionally without normals.
pub fn quad(normals: bool) -> MeshData {
    MeshData {
        positions: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        normals: normals.then(|| vec![[0.0, 0.0, 1.0]; 4]),
        uvs: Some(vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]),
        indices: Some(vec![0, 1, 2, 2, 3, 0]),
    }
}

pub fn emissive_material(strength: f64) -> Value {
    json!({
        "pbrMetallicRoughness": { "baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0 },
        "emissiveFactor": [1.0, 0.5, 0.25],
        "extensions": { "KHR_materials_emissive_strength": { "emissiveStrength": strength } }
    })
}

/// A builder with one quad mesh in one root node.
pub fn one_quad() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let m = b.add_material(emissive_material(4.0));
    let mesh = b.add_mesh("quad", &quad(true), Some(m));
    let n = b.add_node(json!({ "mesh": mesh }));
    b.add_root(n);
    b
}

pub fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).expect("write test file");
    p
}

/// Writes JSON with the builder's buffer embedded.
pub fn write_json(dir: &Path, name: &str, doc: &Value) -> PathBuf {
    write(dir, name, &serde_json::to_vec_pretty(doc).expect("json"))
}

pub fn embedded_uri(bin: &[u8]) -> String {
    // Reuse the preset writer's encoder through a throwaway builder round trip.
    let mut b = GltfBuilder::new();
    b.add_view(bin);
    let doc: Value =
        serde_json::from_slice(&b.to_gltf_embedded()).expect("builder writes valid json");
    doc["buffers"][0]["uri"]
        .as_str()
        .unwrap_or_default()
        .to_string()
}

/// A `size` x `size` PNG of one RGBA colour.
pub fn solid_png(size: u32, rgba: [u8; 4]) -> Vec<u8> {
    let mut png = Vec::new();
    image::RgbaImage::from_pixel(size, size, image::Rgba(rgba))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .expect("encode");
    png
}

/// Asserts that `text` contains each of `parts`.
pub fn assert_contains(text: &str, parts: &[&str]) {
    for part in parts {
        assert!(text.contains(part), "{text:?} lacks {part:?}");
    }
}

/// Loads quietly.
pub fn load(path: &Path) -> Result<Scene, blueshift_scene::SceneError> {
    Scene::load_with(
        path,
        &blueshift_scene::LoadOptions {
            quiet: true,
            ..Default::default()
        },
    )
}

/// How many triangles the scene at `p` has; it must load (with `options`, else quietly).
pub fn triangles(p: &Path, options: Option<&blueshift_scene::LoadOptions>) -> usize {
    let scene = match options {
        Some(o) => Scene::load_with(p, o),
        None => load(p),
    };
    scene.expect("the scene loads").triangles.len()
}

/// The one-quad scene's JSON, its buffer embedded.
pub fn quad_doc() -> Value {
    let b = one_quad();
    b.json(Some(embedded_uri(b.bin())))
}

/// Loads a scene from memory, quietly, within `budget`.
pub fn load_budgeted(bytes: &[u8], budget: LoadBudget) -> Result<Scene, SceneError> {
    let options = LoadOptions {
        quiet: true,
        budget,
        ..Default::default()
    };
    Scene::from_slice(bytes, None, &options)
}
