//! Unit shapes and procedural textures for the presets.

use super::builder::MeshData;
use glam::{DMat3, DQuat, DVec3};
use serde_json::{Value, json};

/// The square [-1, 1]^2 in the z = 0 plane, facing +z (like Mitsuba's `rectangle`).
pub(crate) fn rectangle(uv_scale: f32) -> MeshData {
    let s = uv_scale;
    MeshData {
        positions: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        normals: Some(vec![[0.0, 0.0, 1.0]; 4]),
        uvs: Some(vec![[0.0, s], [s, s], [s, 0.0], [0.0, 0.0]]),
        indices: Some(vec![0, 1, 2, 2, 3, 0]),
    }
}

/// The cube [-1, 1]^3 with 24 vertices, outward face normals, counter-clockwise faces seen
/// from outside (like Mitsuba's `cube`).
pub(crate) fn cube() -> MeshData {
    let mut m = MeshData {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        indices: Some(Vec::new()),
        ..Default::default()
    };
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut n = [0.0f32; 3];
            n[axis] = sign;
            let (mut a, mut b) = ((axis + 1) % 3, (axis + 2) % 3);
            if sign < 0.0 {
                std::mem::swap(&mut a, &mut b);
            }
            let base = m.positions.len() as u32;
            for (du, dv) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let mut p = n;
                p[a] = du;
                p[b] = dv;
                m.positions.push(p);
                push(&mut m.normals, n);
                push(&mut m.uvs, [(du + 1.0) * 0.5, (1.0 - dv) * 0.5]);
            }
            if let Some(ix) = &mut m.indices {
                ix.extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
            }
        }
    }
    m
}

/// The unit sphere as a latitude-longitude mesh (`segments` around, `rings` pole to pole).
pub(crate) fn uv_sphere(segments: u32, rings: u32) -> MeshData {
    let mut m = MeshData {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        indices: Some(Vec::new()),
        ..Default::default()
    };
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..=segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            let p = [
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ];
            m.positions.push(p);
            push(&mut m.normals, p);
            push(
                &mut m.uvs,
                [s as f32 / segments as f32, r as f32 / rings as f32],
            );
        }
    }
    let row = segments + 1;
    if let Some(ix) = &mut m.indices {
        for r in 0..rings {
            for s in 0..segments {
                let (a, b) = (r * row + s, (r + 1) * row + s);
                if r != 0 {
                    ix.extend_from_slice(&[a, b, a + 1]);
                }
                if r != rings - 1 {
                    ix.extend_from_slice(&[a + 1, b, b + 1]);
                }
            }
        }
    }
    m
}

fn push<T>(v: &mut Option<Vec<T>>, x: T) {
    if let Some(v) = v {
        v.push(x);
    }
}

/// A node transform `T * R(axis, degrees) * S` in glTF TRS form.
pub(crate) fn trs(translation: [f64; 3], axis: [f64; 3], degrees: f64, scale: [f64; 3]) -> Value {
    let q = DQuat::from_axis_angle(DVec3::from(axis).normalize(), degrees.to_radians());
    json!({ "translation": translation, "rotation": q.to_array(), "scale": scale })
}

/// A camera node transform looking from `eye` at `target` (glTF cameras look down -z).
pub(crate) fn look_at(eye: [f64; 3], target: [f64; 3], up: [f64; 3]) -> Value {
    let (eye, target, up) = (DVec3::from(eye), DVec3::from(target), DVec3::from(up));
    let back = (eye - target).normalize();
    let right = up.cross(back).normalize();
    let up = back.cross(right);
    let q = DQuat::from_mat3(&DMat3::from_cols(right, up, back));
    json!({ "translation": eye.to_array(), "rotation": q.to_array() })
}

/// A small deterministic hash to [0, 1).
fn hash(x: u32, y: u32, seed: u32) -> f32 {
    let mut h =
        x.wrapping_mul(0x8da6_b343) ^ y.wrapping_mul(0xd816_3841) ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// RGBA8 image from a per-pixel colour function (components in [0, 1]).
pub(crate) fn image(size: u32, f: impl Fn(u32, u32) -> [f32; 3]) -> Vec<u8> {
    let mut out = Vec::with_capacity((size * size * 4) as usize);
    for y in 0..size {
        for x in 0..size {
            let c = f(x, y);
            out.extend(c.iter().map(|v| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8));
            out.push(255);
        }
    }
    out
}

/// Checkerboard with `cell`-pixel squares of two colours.
pub(crate) fn checker(size: u32, cell: u32, a: [f32; 3], b: [f32; 3]) -> Vec<u8> {
    image(
        size,
        |x, y| if (x / cell + y / cell) % 2 == 0 { a } else { b },
    )
}

/// Per-pixel colour noise: white noise in hue and brightness, maximal high frequencies.
pub(crate) fn noise(size: u32, seed: u32) -> Vec<u8> {
    image(size, |x, y| {
        let v = 0.15 + 0.85 * hash(x, y, seed);
        [
            v * (0.5 + 0.5 * hash(x, y, seed + 1)),
            v * 0.8,
            v * (0.5 + 0.5 * hash(x, y, seed + 2)),
        ]
    })
}

/// Stripes of `period` pixels, thin dark lines on a light colour.
pub(crate) fn stripes(size: u32, period: u32, color: [f32; 3]) -> Vec<u8> {
    image(size, |x, y| {
        if (x + y) % period < period / 3 {
            [0.05, 0.05, 0.05]
        } else {
            color
        }
    })
}

/// Roughness/metallic map (glTF: G = roughness, B = metallic) in blocks of `cell` pixels.
pub(crate) fn roughness_blocks(size: u32, cell: u32, seed: u32) -> Vec<u8> {
    image(size, |x, y| {
        let r = 0.1 + 0.9 * hash(x / cell, y / cell, seed);
        [
            0.0,
            r,
            if hash(x / cell, y / cell, seed + 7) > 0.7 {
                1.0
            } else {
                0.0
            },
        ]
    })
}

/// PNG-encodes an RGBA8 image.
pub(crate) fn png(rgba: &[u8], size: u32) -> Result<Vec<u8>, image::ImageError> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out).write_image(
        rgba,
        size,
        size,
        image::ExtendedColorType::Rgba8,
    )?;
    Ok(out)
}
