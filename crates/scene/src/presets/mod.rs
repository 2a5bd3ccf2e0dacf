//! Bundled scenes, generated in code and written as self-contained `.gltf` files (JSON with
//! the buffer and PNG textures embedded as a base64 data URI). Output bytes are deterministic.
//!
//! - `cornell-box`: Mitsuba 3's `mi.cornell_box()` (same walls, boxes, light, reflectances,
//!   radiance and sensor; fov 39.3077 deg on the smaller axis, i.e. yfov for square images;
//!   pure Lambert materials via KHR_materials_specular `specularFactor` 0, as Mitsuba's
//!   `diffuse` BSDF).
//! - `textured`: high-frequency checker / noise / stripe textures on a floor, a cube and a
//!   sphere, an area light and a constant environment (scene extras).
//! - `edges`: a fence of thin posts, rails and slats before columns and a back wall: many
//!   depth edges; one area light.

mod base64;
mod builder;
pub mod hostile;
mod shapes;

pub use builder::{GltfBuilder, MeshData, glb};

use crate::{Result, SceneError};
use serde_json::{Value, json};
use shapes::{
    checker, cube, look_at, noise, png, rectangle, roughness_blocks, stripes, trs, uv_sphere,
};
use std::path::{Path, PathBuf};

/// Names accepted by [`write_preset`].
pub const PRESETS: &[&str] = &["cornell-box", "textured", "edges"];

/// Writes preset `name` to `dir/<name>.gltf` (creating `dir`) and returns the path. The file
/// is written to a temporary name first and renamed, so it is never left half-written.
pub fn write_preset(name: &str, dir: &Path) -> Result<PathBuf> {
    let bytes = preset_bytes(name)?;
    let path = dir.join(format!("{name}.gltf"));
    let tmp = dir.join(format!(".{name}.gltf.tmp"));
    let write_err = |source| SceneError::Write {
        path: path.clone(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(write_err)?;
    std::fs::write(&tmp, &bytes).map_err(write_err)?;
    std::fs::rename(&tmp, &path).map_err(write_err)?;
    Ok(path)
}

/// The `.gltf` bytes of preset `name`.
pub fn preset_bytes(name: &str) -> Result<Vec<u8>> {
    let builder = match name {
        "cornell-box" => cornell_box(),
        "textured" => textured(),
        "edges" => edges(),
        _ => {
            return Err(SceneError::UnknownPreset {
                name: name.to_string(),
                available: PRESETS.join(", "),
            });
        }
    };
    Ok(builder.to_gltf_embedded())
}

/// A non-metallic material with a base colour, optionally emissive (radiance, linear RGB).
fn material(name: &str, rgb: [f64; 3], emission: Option<[f64; 3]>) -> Value {
    let mut m = json!({
        "name": name,
        "pbrMetallicRoughness": {
            "baseColorFactor": [rgb[0], rgb[1], rgb[2], 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": 1.0
        }
    });
    if let Some(e) = emission {
        // glTF clamps emissiveFactor to [0, 1]; the strength extension carries the scale.
        let strength = e.iter().cloned().fold(0.0, f64::max);
        m["emissiveFactor"] = json!(e.map(|c| c / strength));
        m["extensions"] =
            json!({ "KHR_materials_emissive_strength": { "emissiveStrength": strength } });
    }
    m
}

/// `m` without the dielectric specular layer (KHR_materials_specular `specularFactor` 0):
/// pure Lambert, like the `diffuse` BSDF of Mitsuba's Cornell box.
fn lambert(mut m: Value) -> Value {
    m["extensions"]["KHR_materials_specular"] = json!({ "specularFactor": 0.0 });
    m
}

fn node(mesh: usize, transform: Value) -> Value {
    let mut n = transform;
    n["mesh"] = json!(mesh);
    n
}

const X: [f64; 3] = [1.0, 0.0, 0.0];
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// Mitsuba 3 `mi.cornell_box()`: unit rectangles / cubes placed by the same transforms.
fn cornell_box() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let white = b.add_material(lambert(material(
        "white",
        [0.885809, 0.698859, 0.666422],
        None,
    )));
    let green = b.add_material(lambert(material(
        "green",
        [0.105421, 0.37798, 0.076425],
        None,
    )));
    let red = b.add_material(lambert(material(
        "red",
        [0.570068, 0.0430135, 0.0443706],
        None,
    )));
    let light = b.add_material(lambert(material(
        "light",
        [0.885809, 0.698859, 0.666422],
        Some([18.387, 13.9873, 6.75357]),
    )));
    let rect = rectangle(1.0);
    let rect_white = b.add_mesh("rectangle-white", &rect, Some(white));
    let rect_green = b.add_mesh("rectangle-green", &rect, Some(green));
    let rect_red = b.add_mesh("rectangle-red", &rect, Some(red));
    let rect_light = b.add_mesh("rectangle-light", &rect, Some(light));
    let cube_white = b.add_mesh("cube-white", &cube(), Some(white));
    let one = [1.0; 3];
    let parts = [
        (
            "light",
            rect_light,
            trs([0.0, 0.99, 0.01], X, 90.0, [0.23, 0.19, 0.19]),
        ),
        ("floor", rect_white, trs([0.0, -1.0, 0.0], X, -90.0, one)),
        ("ceiling", rect_white, trs([0.0, 1.0, 0.0], X, 90.0, one)),
        ("back", rect_white, trs([0.0, 0.0, -1.0], X, 0.0, one)),
        (
            "green-wall",
            rect_green,
            trs([1.0, 0.0, 0.0], Y, -90.0, one),
        ),
        ("red-wall", rect_red, trs([-1.0, 0.0, 0.0], Y, 90.0, one)),
        (
            "small-box",
            cube_white,
            trs([0.335, -0.7, 0.38], Y, -17.0, [0.3; 3]),
        ),
        (
            "large-box",
            cube_white,
            trs([-0.33, -0.4, -0.28], Y, 18.25, [0.3, 0.61, 0.3]),
        ),
    ];
    for (name, mesh, t) in parts {
        let mut n = node(mesh, t);
        n["name"] = json!(name);
        let i = b.add_node(n);
        b.add_root(i);
    }
    let cam = b.add_camera(39.3077f64.to_radians(), 1.0);
    let c = b.add_node(json!({ "name": "sensor", "camera": cam, "translation": [0.0, 0.0, 3.9] }));
    b.add_root(c);
    b
}

/// High-frequency textures, an area light and a constant environment.
fn textured() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let repeat = json!({ "wrapS": 10497, "wrapT": 10497, "magFilter": 9729 });
    let nearest = json!({ "wrapS": 33071, "wrapT": 33071, "magFilter": 9728 });
    let tex = |b: &mut GltfBuilder, name: &str, rgba: Vec<u8>, size: u32, s: &Value| {
        let bytes = png(&rgba, size).unwrap_or_default();
        b.add_png_texture(name, &bytes, s.clone())
    };
    let checker_t = tex(
        &mut b,
        "checker",
        checker(256, 8, [0.9, 0.9, 0.85], [0.08, 0.08, 0.1]),
        256,
        &repeat,
    );
    let noise_t = tex(&mut b, "noise", noise(128, 7), 128, &nearest);
    let stripes_t = tex(
        &mut b,
        "stripes",
        stripes(256, 6, [0.85, 0.55, 0.2]),
        256,
        &repeat,
    );
    let rough_t = tex(
        &mut b,
        "roughness",
        roughness_blocks(64, 8, 3),
        64,
        &nearest,
    );

    let textured = |name: &str, tex: usize, extra: Value| {
        let mut m = material(name, [1.0, 1.0, 1.0], None);
        m["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": tex });
        if let Value::Object(extra) = extra {
            for (k, v) in extra {
                m["pbrMetallicRoughness"][k] = v;
            }
        }
        m
    };
    let floor_m = b.add_material(textured("checker-floor", checker_t, json!({})));
    let cube_m = b.add_material(textured("noise-cube", noise_t, json!({})));
    let sphere_m = b.add_material(textured(
        "striped-sphere",
        stripes_t,
        json!({ "metallicFactor": 1.0, "metallicRoughnessTexture": { "index": rough_t } }),
    ));
    let wall_m = b.add_material(material("wall", [0.6, 0.6, 0.65], None));
    let light_m = b.add_material(material("light", [1.0; 3], Some([12.0, 10.8, 9.6])));

    let floor = b.add_mesh("floor", &rectangle(8.0), Some(floor_m));
    let wall = b.add_mesh("wall", &rectangle(1.0), Some(wall_m));
    let cube_mesh = b.add_mesh("cube", &cube(), Some(cube_m));
    let sphere = b.add_mesh("sphere", &uv_sphere(48, 24), Some(sphere_m));
    let light = b.add_mesh("light", &rectangle(1.0), Some(light_m));
    for (mesh, t) in [
        (floor, trs([0.0, 0.0, 0.0], X, -90.0, [4.0, 4.0, 1.0])),
        (wall, trs([0.0, 2.0, -3.0], X, 0.0, [4.0, 2.0, 1.0])),
        (cube_mesh, trs([-1.0, 0.5, -0.2], Y, 30.0, [0.5; 3])),
        (sphere, trs([0.9, 0.6, 0.3], Y, 0.0, [0.6; 3])),
        (light, trs([0.0, 3.0, 0.5], X, 90.0, [0.8, 0.8, 1.0])),
    ] {
        let i = b.add_node(node(mesh, t));
        b.add_root(i);
    }
    let cam = b.add_camera(45f64.to_radians(), 1.0);
    let mut c = look_at([0.0, 1.6, 4.5], [0.0, 0.5, 0.0], Y);
    c["camera"] = json!(cam);
    let c = b.add_node(c);
    b.add_root(c);
    b.set_scene_extras(json!({ crate::load::ENVIRONMENT_EXTRAS_KEY: [0.25, 0.3, 0.4] }));
    b
}

/// Thin posts, rails and slats in front of columns and a wall: many depth edges.
fn edges() -> GltfBuilder {
    let mut b = GltfBuilder::new();
    let post_m = b.add_material(material("post", [0.9, 0.88, 0.82], None));
    let column_m = b.add_material(material("column", [0.55, 0.12, 0.1], None));
    let wall_m = b.add_material(material("wall", [0.25, 0.3, 0.45], None));
    let floor_m = b.add_material(material("floor", [0.5, 0.5, 0.5], None));
    let light_m = b.add_material(material("light", [1.0; 3], Some([15.0, 13.0, 10.0])));
    let post = b.add_mesh("post", &cube(), Some(post_m));
    let column = b.add_mesh("column", &cube(), Some(column_m));
    let wall = b.add_mesh("wall", &rectangle(1.0), Some(wall_m));
    let floor = b.add_mesh("floor", &rectangle(1.0), Some(floor_m));
    let light = b.add_mesh("light", &rectangle(1.0), Some(light_m));

    // The fence is a node hierarchy: one parent, children placed relative to it.
    let mut children = Vec::new();
    for i in 0..21 {
        let x = -2.0 + 0.2 * i as f64;
        children.push(b.add_node(node(post, trs([x, 0.8, 0.0], Y, 0.0, [0.015, 0.8, 0.015]))));
    }
    for y in [0.45, 1.35] {
        children.push(b.add_node(node(
            post,
            trs([0.0, y, 0.03], Y, 0.0, [2.05, 0.012, 0.012]),
        )));
    }
    for i in 0..5 {
        let x = -1.6 + 0.8 * i as f64;
        children.push(b.add_node(node(
            post,
            trs([x, 0.9, 0.05], Z, 40.0, [0.5, 0.008, 0.008]),
        )));
    }
    let fence = b
        .add_node(json!({ "name": "fence", "translation": [0.0, 0.0, 0.2], "children": children }));
    b.add_root(fence);
    for (mesh, t) in [
        (column, trs([-1.5, 1.0, -0.8], Y, 0.0, [0.06, 1.0, 0.06])),
        (column, trs([-0.5, 1.0, -0.9], Y, 20.0, [0.06, 1.0, 0.06])),
        (column, trs([0.4, 1.0, -0.7], Y, 45.0, [0.06, 1.0, 0.06])),
        (column, trs([1.3, 1.0, -1.0], Y, 10.0, [0.06, 1.0, 0.06])),
        (wall, trs([0.0, 1.5, -1.5], X, 0.0, [3.0, 1.5, 1.0])),
        (floor, trs([0.0, 0.0, 0.0], X, -90.0, [3.0, 3.0, 1.0])),
        (light, trs([0.0, 2.5, 0.8], X, 90.0, [0.6, 0.4, 1.0])),
    ] {
        let i = b.add_node(node(mesh, t));
        b.add_root(i);
    }
    let cam = b.add_camera(40f64.to_radians(), 1.0);
    let mut c = look_at([0.3, 1.0, 3.2], [0.0, 0.9, 0.0], Y);
    c["camera"] = json!(cam);
    let c = b.add_node(c);
    b.add_root(c);
    b
}
