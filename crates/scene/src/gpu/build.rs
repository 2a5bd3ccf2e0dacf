//! [`SceneGpu`]: the scene flattened into upload-ready buffers.

use super::lights::{EnvGpu, non_triangle_lights};
use super::*;
use crate::geometry::{luminance, srgb_to_linear};
use crate::limits::check_sizes;
use crate::scene::{Scene, Wrap};
use crate::{Aabb, Bvh, Result, intersect};
use rayon::prelude::*;

/// Everything the GPU needs, ready to upload. Triangle-indexed arrays are in BVH order.
#[derive(Clone, Debug, Default)]
pub struct SceneGpu {
    pub nodes: Vec<BvhNode>,
    pub triangles: Vec<GpuTriangle>,
    pub shading: Vec<TriangleShading>,
    pub materials: Vec<GpuMaterial>,
    pub textures: Vec<GpuTexture>,
    /// All texture images, one RGBA8 `u32` per texel (the scene's own images, shared).
    pub atlas: Atlas,
    pub lights: Vec<GpuLight>,
    /// Records of the lights that are not triangles (`GpuLight::triangle` indexes them).
    pub light_params: Vec<LightParams>,
    /// The environment map and its sampling tables, if the scene has a map.
    pub environment: Option<EnvGpu>,
    pub info: SceneInfo,
    /// `bvh_order[i]` is the index in [`Scene::triangles`] of GPU triangle `i`.
    pub bvh_order: Vec<u32>,
    /// Depth of the deepest BVH leaf.
    pub bvh_depth: u32,
}

impl SceneGpu {
    /// Builds the BVH (in parallel) and flattens the scene.
    pub fn build(scene: &Scene) -> SceneGpu {
        let bvh = Bvh::build_with(scene.triangles.len(), |i| {
            Aabb::from_points(&scene.triangles[i].positions)
        });

        let triangles: Vec<GpuTriangle> = bvh
            .order
            .par_iter()
            .map(|&i| {
                let p = scene.triangles[i as usize].positions;
                GpuTriangle {
                    v0: p[0],
                    e1: p[1] - p[0],
                    e2: p[2] - p[0],
                }
            })
            .collect();

        let atlas = Atlas::new(scene.images.clone());
        let image_means: Vec<Vec3> = scene
            .images
            .iter()
            .map(|img| mean_linear_rgb(&img.rgba8))
            .collect();
        let wrap_bits = |w: Wrap| match w {
            Wrap::Repeat => TEXTURE_WRAP_REPEAT,
            Wrap::Clamp => TEXTURE_WRAP_CLAMP,
            Wrap::Mirror => TEXTURE_WRAP_MIRROR,
        };
        let textures: Vec<GpuTexture> = scene
            .textures
            .iter()
            .map(|t| {
                // A dangling image index (hand-built scenes only) becomes a 0x0 texture.
                let i = t.image as usize;
                let (w, h) = scene
                    .images
                    .get(i)
                    .map_or((0, 0), |img| (img.width, img.height));
                GpuTexture {
                    offset: atlas.offset(i).unwrap_or(0) as u32,
                    width: w,
                    height: h,
                    flags: wrap_bits(t.wrap_s) << TEXTURE_WRAP_S_SHIFT
                        | wrap_bits(t.wrap_t) << TEXTURE_WRAP_T_SHIFT
                        | if t.nearest { TEXTURE_FILTER_NEAREST } else { 0 },
                }
            })
            .collect();
        let tex_index = |t: Option<u32>| t.map_or(-1, |t| t as i32);
        let materials: Vec<GpuMaterial> = scene
            .materials
            .iter()
            .map(|m| GpuMaterial {
                base_color: m.base_color,
                emissive: m.emissive,
                metallic: m.metallic,
                roughness: m.roughness,
                base_color_tex: tex_index(m.base_color_texture),
                emissive_tex: tex_index(m.emissive_texture),
                mr_tex: tex_index(m.metallic_roughness_texture),
                flags: if m.double_sided {
                    MATERIAL_DOUBLE_SIDED
                } else {
                    0
                },
                specular_color: m.specular_color,
                specular: m.specular,
            })
            .collect();

        // Emitted radiance per material (texture approximated by its mean).
        let material_emission: Vec<Vec3> = scene
            .materials
            .iter()
            .map(|m| {
                let tex = m
                    .emissive_texture
                    .map(|t| {
                        let image = scene.textures.get(t as usize).map(|t| t.image as usize);
                        image
                            .and_then(|i| image_means.get(i))
                            .copied()
                            .unwrap_or(Vec3::ZERO)
                    })
                    .unwrap_or(Vec3::ONE);
                m.emissive * tex
            })
            .collect();

        let mut shading = Vec::with_capacity(triangles.len());
        let mut emitters = Vec::new();
        let mut emitter_power = Vec::new();
        for (i, &src) in bvh.order.iter().enumerate() {
            let t = &scene.triangles[src as usize];
            let emission = material_emission
                .get(t.material as usize)
                .copied()
                .unwrap_or(Vec3::ZERO);
            let face = (t.positions[1] - t.positions[0]).cross(t.positions[2] - t.positions[0]);
            let area = 0.5 * face.length();
            let power = luminance(emission) as f64 * area as f64 * std::f64::consts::PI;
            if power > 0.0 && power.is_finite() {
                // The side `triangle_light_point` calls the front: the face normal turned
                // towards the first shading normal.
                let facing = if face.dot(t.normals[0]) < 0.0 {
                    -face
                } else {
                    face
                };
                let textured = scene
                    .materials
                    .get(t.material as usize)
                    .is_some_and(|m| m.emissive_texture.is_some());
                emitters.push(quads::Emitter {
                    index: i as u32,
                    positions: t.positions,
                    material: t.material,
                    facing,
                    textured,
                });
                emitter_power.push((power, area));
            }
            shading.push(TriangleShading {
                n0: t.normals[0],
                n1: t.normals[1],
                n2: t.normals[2],
                uv0: t.uvs[0],
                uv1: t.uvs[1],
                uv2: t.uvs[2],
                material: t.material,
                light: -1,
            });
        }
        let mut lights = Vec::new();
        let mut total = 0f64;
        let mut powers = Vec::new();
        for light in quads::pair_emitters(&emitters) {
            let (first, second, code) = match light {
                quads::Emissive::Triangle(a) => (a, None, 0),
                quads::Emissive::Quad(a, b, frame) => (a, Some(b), frame.code()),
            };
            let members = std::iter::once(first).chain(second);
            let (power, area) = members.clone().fold((0.0, 0.0), |(p, a), m| {
                (p + emitter_power[m].0, a + emitter_power[m].1)
            });
            for m in members {
                shading[emitters[m].index as usize].light = lights.len() as i32;
            }
            total += power;
            powers.push(power);
            lights.push(GpuLight {
                triangle: emitters[first].index | code << quads::LIGHT_QUAD_SHIFT,
                area,
                pdf: 0.0,
                cdf: 0.0,
            });
        }
        let bounds = scene.bounds();
        let radius = if bounds.is_empty() {
            0.0
        } else {
            0.5 * (bounds.max - bounds.min).length()
        };
        let (light_params, environment, env_light) =
            non_triangle_lights(scene, radius, &mut lights, &mut powers, &mut total);
        let mut running = 0f64;
        let last = lights.len().saturating_sub(1);
        for (k, (l, p)) in lights.iter_mut().zip(&powers).enumerate() {
            running += p;
            l.pdf = (p / total) as f32;
            l.cdf = if k == last {
                1.0
            } else {
                (running / total) as f32
            };
        }

        let light_params_offset = lights.len() as u32;
        // Without a map the shader's (discarded) map reads land in the first record.
        let env_offset = if environment.is_some() {
            light_params_offset + LIGHT_PARAMS_TEXELS * light_params.len().max(1) as u32
        } else {
            light_params_offset
        };
        let map = scene.environment_map.as_deref();
        let info = SceneInfo {
            triangle_count: triangles.len() as u32,
            node_count: bvh.nodes.len() as u32,
            material_count: materials.len() as u32,
            texture_count: textures.len() as u32,
            light_count: lights.len() as u32,
            texel_count: atlas.len() as u32,
            total_light_power: total as f32,
            environment: scene.environment,
            bounds_min: if bounds.is_empty() {
                Vec3::ZERO
            } else {
                bounds.min
            },
            bounds_max: if bounds.is_empty() {
                Vec3::ZERO
            } else {
                bounds.max
            },
            light_params_offset,
            env_offset,
            env_width: map.map_or(0, |m| m.width),
            env_height: map.map_or(0, |m| m.height),
            env_light,
            env_rotation: map.map_or(Vec2::new(1.0, 0.0), |m| m.rotation_cs()),
        };
        SceneGpu {
            nodes: bvh.nodes,
            triangles,
            shading,
            materials,
            textures,
            atlas,
            lights,
            light_params,
            environment,
            info,
            bvh_order: bvh.order,
            bvh_depth: bvh.depth,
        }
    }

    /// The BVH as a [`Bvh`] view (nodes and order), e.g. for [`Bvh::validate`].
    pub fn bvh(&self) -> Bvh {
        Bvh {
            nodes: self.nodes.clone(),
            order: self.bvh_order.clone(),
            depth: self.bvh_depth,
        }
    }

    /// Bytes of each array as a storage buffer (an empty one padded to one element), with
    /// its name for errors, in binding order (nodes, triangles, shading, materials, textures,
    /// texels, lights): what `check_limits` holds to `maxStorageBufferRange`.
    pub fn buffer_sizes(&self) -> [(&'static str, u64); 7] {
        fn bytes<T>(len: usize) -> u64 {
            (len.max(1) * size_of::<T>()) as u64
        }
        [
            ("BVH node", bytes::<BvhNode>(self.nodes.len())),
            ("BVH triangle", bytes::<GpuTriangle>(self.triangles.len())),
            (
                "triangle shading",
                bytes::<TriangleShading>(self.shading.len()),
            ),
            ("material", bytes::<GpuMaterial>(self.materials.len())),
            ("texture table", bytes::<GpuTexture>(self.textures.len())),
            ("texel", bytes::<u32>(self.atlas.len())),
            ("light", bytes::<GpuLight>(self.lights.len())),
        ]
    }

    /// Errors with the first array larger than `maxStorageBufferRange`.
    pub fn check_limits(&self, max_storage_buffer_range: u64) -> Result<()> {
        check_sizes(&self.buffer_sizes(), max_storage_buffer_range)
    }

    /// Closest hit (CPU twin of `bvh_closest_hit`).
    pub fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        intersect::closest_hit(&self.nodes, &self.triangles, ray)
    }

    /// Any hit in `[ray.tmin, ray.tmax]` (CPU twin of `bvh_occluded`).
    pub fn occluded(&self, ray: &Ray) -> bool {
        intersect::occluded(&self.nodes, &self.triangles, ray)
    }

    /// Reference intersector: every triangle, no BVH.
    pub fn closest_hit_brute_force(&self, ray: &Ray) -> Option<Hit> {
        intersect::closest_hit_brute_force(&self.triangles, ray)
    }

    /// Closest hits of many rays, in parallel.
    pub fn trace_rays(&self, rays: &[Ray]) -> Vec<Option<Hit>> {
        rays.par_iter().map(|r| self.closest_hit(r)).collect()
    }

    /// Closest hits in the exact encoding `bvh_trace.comp` writes (misses as [`Hit::miss`]),
    /// for a direct comparison with the GPU output buffer.
    pub fn trace_rays_raw(&self, rays: &[Ray]) -> Vec<Hit> {
        rays.par_iter()
            .map(|r| self.closest_hit(r).unwrap_or_else(|| Hit::miss(r)))
            .collect()
    }

    /// Occlusion of many rays, as `bvh_trace.comp` writes it (1 = occluded).
    pub fn occluded_rays(&self, rays: &[Ray]) -> Vec<u32> {
        rays.par_iter().map(|r| self.occluded(r) as u32).collect()
    }
}

/// Mean linear RGB of an sRGB RGBA8 image.
fn mean_linear_rgb(rgba: &[u8]) -> Vec3 {
    let lut: Vec<f32> = (0..=255u8).map(srgb_to_linear).collect();
    let n = rgba.len() / 4;
    if n == 0 {
        return Vec3::ZERO;
    }
    let mut sum = [0f64; 3];
    for c in rgba.chunks_exact(4) {
        for k in 0..3 {
            sum[k] += lut[c[k] as usize] as f64;
        }
    }
    Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32) / n as f32
}
