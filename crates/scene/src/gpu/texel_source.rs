//! The scene's texel arrays (layout: the `texels` module), written on demand a range at a
//! time straight into the caller's buffer: an upload goes through one small staging chunk, so
//! the host never holds a second, repacked copy of the scene (for a million triangles that
//! copy was 160 MB; for an 8192 x 4096 environment map, 512 MB).

use super::*;

/// Which array of [`SceneGpu`] a [`TexelSource`] writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Array {
    Nodes,
    Triangles,
    Shading,
    Materials,
    Textures,
    Texels,
    Lights,
}

/// One texel array of a scene: its name, length and contents, written on demand.
#[derive(Clone, Copy, Debug)]
pub struct TexelSource<'a> {
    /// Name for the image ("scene.bvh_nodes").
    pub name: &'static str,
    scene: &'a SceneGpu,
    array: Array,
    len: usize,
}

impl TexelSource<'_> {
    /// Texels in the array: never 0 (an empty array is one zeroed texel, or an empty box for
    /// BVH nodes).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Always false (see [`Self::len`]); for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Image size `(width, height)`: [`SCENE_TEXELS_WIDTH`] wide (narrower if shorter).
    pub fn extent(&self) -> (u32, u32) {
        let n = self.len as u32;
        (n.min(SCENE_TEXELS_WIDTH), n.div_ceil(SCENE_TEXELS_WIDTH))
    }

    /// Writes texels `first .. first + out.len()` of the array into `out` (none past the end:
    /// `out` is cut to what is left).
    pub fn write(&self, first: usize, out: &mut [Texel]) {
        let end = self.len.min(first.saturating_add(out.len()));
        let out = &mut out[..end.saturating_sub(first)];
        let g = self.scene;
        match self.array {
            Array::Nodes => fill(out, first, |k| match k.checked_sub(2) {
                // One node of padding first.
                None => [0; 4],
                Some(k) => {
                    let n = g.nodes.get(k / 2).unwrap_or(&BvhNode::EMPTY);
                    node_texels(n)[k % 2]
                }
            }),
            Array::Triangles => fill(out, first, |k| {
                let (i, part) = (k / 4, k % 4);
                match (g.triangles.get(i), g.shading.get(i)) {
                    (Some(t), Some(s)) => triangle_texels(t, s)[part],
                    _ => [0; 4],
                }
            }),
            Array::Shading => fill(out, first, |k| {
                g.shading
                    .get(k / 4)
                    .map_or([0; 4], |s| shading_texels(s)[k % 4])
            }),
            Array::Materials => fill(out, first, |k| {
                g.materials
                    .get(k / 4)
                    .map_or([0; 4], |m| material_texels(m)[k % 4])
            }),
            Array::Textures => fill(out, first, |k| {
                g.textures
                    .get(k)
                    .map_or([0; 4], |t| [t.offset, t.width, t.height, t.flags])
            }),
            Array::Texels => {
                g.atlas.write(
                    first * ATLAS_WORDS_PER_TEXEL as usize,
                    bytemuck::cast_slice_mut(out),
                );
            }
            Array::Lights => write_lights(g, first, out),
        }
    }

    /// The whole array (tests; an upload writes it a chunk at a time).
    pub fn to_vec(&self) -> Vec<Texel> {
        let mut v = vec![[0; 4]; self.len];
        self.write(0, &mut v);
        v
    }
}

/// `out[i] = texel(first + i)`.
fn fill(out: &mut [Texel], first: usize, texel: impl Fn(usize) -> Texel) {
    for (i, t) in out.iter_mut().enumerate() {
        *t = texel(first + i);
    }
}

fn f(x: f32) -> u32 {
    x.to_bits()
}

/// The light image: the [`GpuLight`]s, the [`LightParams`] records (at least one), then the
/// environment map's region.
fn write_lights(g: &SceneGpu, first: usize, out: &mut [Texel]) {
    let lights = g.lights.len();
    let records = g.light_params.len().max(1);
    let params_end = lights + LIGHT_PARAMS_TEXELS as usize * records;
    let zero = LightParams::default();
    for (i, t) in out.iter_mut().enumerate() {
        let k = first + i;
        if k >= params_end {
            // The rest is the map's, written a row at a time below.
            if let Some(env) = &g.environment {
                env.write(k - params_end, &mut out[i..]);
            }
            return;
        }
        *t = match g.lights.get(k) {
            Some(l) => [l.triangle, f(l.area), f(l.pdf), f(l.cdf)],
            None => {
                let r = k - lights;
                let p = g.light_params.get(r / 3).unwrap_or(&zero);
                let v = |a: Vec3, w: u32| [f(a.x), f(a.y), f(a.z), w];
                [
                    v(p.position, p.kind),
                    v(p.direction, f(p.cos_inner)),
                    v(p.intensity, f(p.cos_outer)),
                ][r % 3]
            }
        };
    }
}

pub(super) fn node_texels(n: &BvhNode) -> [Texel; 2] {
    [
        [
            f(n.aabb_min.x),
            f(n.aabb_min.y),
            f(n.aabb_min.z),
            n.left_first,
        ],
        [
            f(n.aabb_max.x),
            f(n.aabb_max.y),
            f(n.aabb_max.z),
            n.count | n.skip << NODE_COUNT_BITS,
        ],
    ]
}

fn triangle_texels(t: &GpuTriangle, s: &TriangleShading) -> [Texel; 4] {
    [
        [f(t.v0.x), f(t.v0.y), f(t.v0.z), f(t.e1.x)],
        [f(t.e1.y), f(t.e1.z), f(t.e2.x), f(t.e2.y)],
        [f(t.e2.z), s.material, s.light as u32, 0],
        [0; 4],
    ]
}

fn shading_texels(s: &TriangleShading) -> [Texel; 4] {
    [
        [f(s.n0.x), f(s.n0.y), f(s.n0.z), f(s.uv0.x)],
        [f(s.n1.x), f(s.n1.y), f(s.n1.z), f(s.uv0.y)],
        [f(s.n2.x), f(s.n2.y), f(s.n2.z), f(s.uv1.x)],
        [f(s.uv1.y), f(s.uv2.x), f(s.uv2.y), 0],
    ]
}

fn material_texels(m: &GpuMaterial) -> [Texel; 4] {
    let c = m.base_color;
    [
        [f(c[0]), f(c[1]), f(c[2]), f(m.metallic)],
        [
            f(m.emissive.x),
            f(m.emissive.y),
            f(m.emissive.z),
            f(m.roughness),
        ],
        [
            m.flags,
            m.base_color_tex as u32,
            m.emissive_tex as u32,
            m.mr_tex as u32,
        ],
        [
            f(m.specular_color.x),
            f(m.specular_color.y),
            f(m.specular_color.z),
            f(m.specular),
        ],
    ]
}

impl SceneGpu {
    /// The scene's texel arrays, in binding order of the trace shader (nodes, triangles,
    /// shading, materials, textures, texels, lights).
    pub fn texel_sources(&self) -> [TexelSource<'_>; 7] {
        let per = |n: usize, k: u32| (n * k as usize).max(1);
        let env = self.environment.as_ref().map_or(0, |e| e.texel_count());
        let lights =
            self.lights.len() + LIGHT_PARAMS_TEXELS as usize * self.light_params.len().max(1) + env;
        let source = |name, array, len| TexelSource {
            name,
            scene: self,
            array,
            len,
        };
        [
            source(
                "scene.bvh_nodes",
                Array::Nodes,
                NODE_TEXELS as usize * (self.nodes.len().max(1) + 1),
            ),
            source(
                "scene.bvh_triangles",
                Array::Triangles,
                // (Written from both arrays: as many triangles as both hold.)
                per(
                    self.triangles.len().min(self.shading.len()),
                    TRIANGLE_TEXELS,
                ),
            ),
            source(
                "scene.triangle_shading",
                Array::Shading,
                per(self.shading.len(), SHADING_TEXELS),
            ),
            source(
                "scene.materials",
                Array::Materials,
                per(self.materials.len(), MATERIAL_TEXELS),
            ),
            source(
                "scene.textures",
                Array::Textures,
                per(self.textures.len(), TEXTURE_TEXELS),
            ),
            source(
                "scene.texels",
                Array::Texels,
                self.atlas
                    .len()
                    .div_ceil(ATLAS_WORDS_PER_TEXEL as usize)
                    .max(1),
            ),
            source("scene.lights", Array::Lights, lights),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{EnvMap, EnvSampling, Scene};
    use std::sync::Arc;

    #[test]
    fn chunks_of_any_size_write_the_whole_array() {
        let root = std::env::var("CARGO_MANIFEST_DIR").expect("manifest dir");
        let mut scene = Scene::load(format!("{root}/../../assets/scenes/textured.gltf"))
            .expect("textured preset");
        let mut map = EnvMap::constant(13, 5, Vec3::ONE);
        for (k, t) in map.texels.iter_mut().enumerate() {
            *t = Vec3::new(k as f32, (k % 3) as f32, 0.5);
        }
        scene.environment_map = Some(Arc::new(map));
        for sampling in EnvSampling::ALL {
            scene.environment_sampling = sampling;
            let g = SceneGpu::build(&scene);
            // The map's region: the tables' marginal, then each texel with its conditional.
            let map = scene.environment_map.as_deref().expect("map");
            let tables = map.tables_for(sampling);
            let lights = g.texel_sources()[6].to_vec();
            let env = &lights[g.info.env_offset as usize..];
            let marginal = tables.marginal.iter().map(|&m| [f(m), 0, 0, 0]);
            let texels = map.texels.iter().zip(&tables.conditional);
            let texels = texels.map(|(c, &p)| [f(c.x), f(c.y), f(c.z), f(p)]);
            assert!(
                env.iter().copied().eq(marginal.chain(texels)),
                "{sampling:?}"
            );
            for s in g.texel_sources() {
                let whole = s.to_vec();
                assert_eq!(whole.len(), s.len());
                // Chunks that split rows of the map (13 wide) and elements (4 texels).
                for chunk in [1, 3, 7, 64] {
                    let mut parts = vec![];
                    for first in (0..s.len()).step_by(chunk) {
                        let mut out = vec![[7; 4]; chunk];
                        s.write(first, &mut out);
                        out.truncate(chunk.min(s.len() - first));
                        parts.extend(out);
                    }
                    assert_eq!(parts, whole, "{} in chunks of {chunk}", s.name);
                }
                // Nothing is written past the end.
                let mut out = vec![[7; 4]; 4];
                s.write(s.len() - 1, &mut out);
                assert_eq!(out[0], whole[s.len() - 1]);
                assert_eq!(out[1..], [[7; 4]; 3]);
            }
        }
    }
}
