//! The scene as `rgba32ui` texels for storage images: the layout the path-tracing shader reads
//! (`shaders/include/scene_texels.glsl` decodes exactly this; keep the two in sync).
//!
//! Why images: on lavapipe (llvmpipe), a storage-buffer load whose address differs between the
//! 8 SIMD lanes is a scalar loop over the lanes with a bounds check per component, while an
//! image load is a straight-line gather. A 32-byte record costs about 4x less from an image
//! (measured), and BVH traversal and shading are dominated by such loads.
//!
//! Every array becomes a list of texels (four `u32`, floats as their bits); element `i` of an
//! array with `N` texels per element occupies texels `N*i .. N*i + N`. Texel `k` lives at
//! `(k % SCENE_TEXELS_WIDTH, k / SCENE_TEXELS_WIDTH)` of its image.
//!
//! | array      | texels | layout                                                               |
//! |------------|--------|----------------------------------------------------------------------|
//! | BVH node   | 2      | `(min.xyz, left_first)`, `(max.xyz, count | skip << 3)` ([`BvhNode`]), from texel 2 |
//! | triangle   | 4      | `(v0.xyz, e1.x)`, `(e1.yz, e2.xy)`, `(e2.z, material, light, 0)`, `(0, 0, 0, 0)` |
//! | shading    | 4      | `(n0.xyz, uv0.x)`, `(n1.xyz, uv0.y)`, `(n2.xyz, uv1.x)`, `(uv1.y, uv2.xy, 0)` |
//! | material   | 4      | `(base.rgb, metallic)`, `(emissive.rgb, roughness)`, `(flags, base_tex, emissive_tex, mr_tex)`, `(specular_color.rgb, specular)` |
//! | light      | 1      | `(triangle, area, pdf, cdf)` (= [`GpuLight`]); then the regions below |
//! | texture    | 1      | `(offset, width, height, flags)` (= [`GpuTexture`])                  |
//! | texel      | 1/4    | four packed RGBA8 texels of the atlas per image texel                |
//!
//! The light image holds, after the [`GpuLight`]s: the [`LightParams`] records (3 texels each,
//! `(position, kind)`, `(direction, cos_inner)`, `(intensity, cos_outer)`, from
//! `SceneInfo::light_params_offset`; at least one, zeroed when there are none), then with an
//! environment map, from `SceneInfo::env_offset`: `height` texels `(marginal cdf, 0, 0, 0)`,
//! then `width * height` texels `(r, g, b, conditional cdf)`, row-major, top row first.
//!
//! Node `i` occupies texels `NODE_TEXELS * (i + 1) ..` (texels 0 and 1 are padding), and a
//! triangle 4 texels of which the 4th is padding: the two children of an interior node (at an
//! odd index and the next) are then four texels of one image row, as are the texels of a
//! triangle, so the shader computes one image coordinate per pair or triangle (measured 2%
//! faster on lavapipe: llvmpipe computes and bounds-checks each coordinate separately).
//!
//! A node's `count` (< 8: `MAX_LEAF_SIZE` is 4) shares a word with its `skip` link (< 2^29, like
//! `left_first`: the node image holds fewer texels).
//!
//! `material` and `light` of a triangle are its [`TriangleShading`] fields (the light index as
//! the bits of the `i32`, -1 = none); the base colour's alpha is not stored (unused).

use super::*;

/// log2 of the width of every scene image, in texels.
pub const SCENE_TEXELS_WIDTH_LOG2: u32 = 12;
/// Width of every scene image, in texels (rows are filled completely but the last).
pub const SCENE_TEXELS_WIDTH: u32 = 1 << SCENE_TEXELS_WIDTH_LOG2;
/// Texels per element of each array.
pub const NODE_TEXELS: u32 = 2;
pub const TRIANGLE_TEXELS: u32 = 4;
pub const SHADING_TEXELS: u32 = 4;
pub const MATERIAL_TEXELS: u32 = 4;
pub const LIGHT_TEXELS: u32 = 1;
pub const LIGHT_PARAMS_TEXELS: u32 = 3;
pub const TEXTURE_TEXELS: u32 = 1;
/// Low bits of a node's second texel's `w` that hold `count` (`skip` above them).
pub const NODE_COUNT_BITS: u32 = 3;
/// Atlas texels (RGBA8 words) per image texel.
pub const ATLAS_WORDS_PER_TEXEL: u32 = 4;

/// One image texel.
pub type Texel = [u32; 4];

/// One array of texels and the image extent that holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct TexelArray {
    /// Name for the image ("scene.bvh_nodes").
    pub name: &'static str,
    /// Never empty (an empty array is one zeroed texel, or an empty box for BVH nodes).
    pub texels: Vec<Texel>,
}

impl TexelArray {
    /// Image size `(width, height)`: [`SCENE_TEXELS_WIDTH`] wide (narrower if shorter).
    pub fn extent(&self) -> (u32, u32) {
        let n = self.texels.len() as u32;
        (n.min(SCENE_TEXELS_WIDTH), n.div_ceil(SCENE_TEXELS_WIDTH))
    }

    /// The texels padded to whole image rows, ready for a tightly packed upload.
    pub fn padded(&self) -> Vec<Texel> {
        let (w, h) = self.extent();
        let mut v = self.texels.clone();
        v.resize((w * h) as usize, [0; 4]);
        v
    }
}

/// The scene in texels, one array per image, in binding order of the trace shader.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneTexels {
    pub nodes: TexelArray,
    pub triangles: TexelArray,
    pub shading: TexelArray,
    pub materials: TexelArray,
    pub textures: TexelArray,
    pub texels: TexelArray,
    pub lights: TexelArray,
}

impl SceneTexels {
    /// The arrays in binding order (nodes, triangles, shading, materials, textures, texels,
    /// lights).
    pub fn arrays(&self) -> [&TexelArray; 7] {
        [
            &self.nodes,
            &self.triangles,
            &self.shading,
            &self.materials,
            &self.textures,
            &self.texels,
            &self.lights,
        ]
    }

    /// The largest image side any array needs (must fit the device's maxImageDimension2D).
    pub fn max_extent(&self) -> u32 {
        self.arrays()
            .iter()
            .map(|a| {
                let (w, h) = a.extent();
                w.max(h)
            })
            .max()
            .unwrap_or(1)
    }
}

fn array(name: &'static str, mut texels: Vec<Texel>) -> TexelArray {
    if texels.is_empty() {
        texels.push([0; 4]);
    }
    TexelArray { name, texels }
}

impl SceneGpu {
    /// The scene in the texel layout of the module documentation, whole (tests and tools; an
    /// upload writes each [`TexelSource`] a chunk at a time instead).
    pub fn texels(&self) -> SceneTexels {
        let [
            nodes,
            triangles,
            shading,
            materials,
            textures,
            texels,
            lights,
        ] = self.texel_sources().map(|s| array(s.name, s.to_vec()));
        SceneTexels {
            nodes,
            triangles,
            shading,
            materials,
            textures,
            texels,
            lights,
        }
    }
}

// The texel counts above are what the closures emit.
const _: () = {
    assert!(NODE_TEXELS == 2 && TRIANGLE_TEXELS == 4 && SHADING_TEXELS == 4);
    assert!(SCENE_TEXELS_WIDTH % 4 == 0);
    assert!(MATERIAL_TEXELS == 4 && LIGHT_TEXELS == 1 && TEXTURE_TEXELS == 1);
    assert!(SCENE_TEXELS_WIDTH.is_power_of_two());
};

#[cfg(test)]
mod tests {
    use super::*;

    fn unf(x: u32) -> f32 {
        f32::from_bits(x)
    }

    #[test]
    fn texels_decode_to_the_gpu_structs() {
        let root = std::env::var("CARGO_MANIFEST_DIR").unwrap();
        let dir = format!("{root}/../../assets/scenes");
        let scene = crate::Scene::load(format!("{dir}/textured.gltf")).unwrap();
        let g = SceneGpu::build(&scene);
        let t = g.texels();
        assert_eq!(
            t.nodes.texels.len(),
            (g.nodes.len() + 1) * NODE_TEXELS as usize
        );
        for (i, n) in g.nodes.iter().enumerate() {
            let a = t.nodes.texels[2 * i + 2];
            let b = t.nodes.texels[2 * i + 3];
            // Children pairs start at odd indices: their 4 texels are 4-aligned, in one row.
            assert!(n.count > 0 || n.left_first % 2 == 1);
            assert_eq!(Vec3::new(unf(a[0]), unf(a[1]), unf(a[2])), n.aabb_min);
            assert_eq!(Vec3::new(unf(b[0]), unf(b[1]), unf(b[2])), n.aabb_max);
            assert_eq!((a[3], b[3] & 7, b[3] >> 3), (n.left_first, n.count, n.skip));
        }
        for (i, (tri, s)) in g.triangles.iter().zip(&g.shading).enumerate() {
            let k = TRIANGLE_TEXELS as usize * i;
            let [a, b, c, d] = [0, 1, 2, 3].map(|j| t.triangles.texels[k + j]);
            assert_eq!(d, [0; 4]);
            assert_eq!(Vec3::new(unf(a[0]), unf(a[1]), unf(a[2])), tri.v0);
            assert_eq!(Vec3::new(unf(a[3]), unf(b[0]), unf(b[1])), tri.e1);
            assert_eq!(Vec3::new(unf(b[2]), unf(b[3]), unf(c[0])), tri.e2);
            assert_eq!((c[1], c[2] as i32), (s.material, s.light));
            let k = SHADING_TEXELS as usize * i;
            let [p, q, r, w] = [0, 1, 2, 3].map(|j| t.shading.texels[k + j]);
            assert_eq!(Vec3::new(unf(p[0]), unf(p[1]), unf(p[2])), s.n0);
            assert_eq!(Vec3::new(unf(q[0]), unf(q[1]), unf(q[2])), s.n1);
            assert_eq!(Vec3::new(unf(r[0]), unf(r[1]), unf(r[2])), s.n2);
            assert_eq!(Vec2::new(unf(p[3]), unf(q[3])), s.uv0);
            assert_eq!(Vec2::new(unf(r[3]), unf(w[0])), s.uv1);
            assert_eq!(Vec2::new(unf(w[1]), unf(w[2])), s.uv2);
        }
        for (i, m) in g.materials.iter().enumerate() {
            let [a, b, c, d] = [0, 1, 2, 3].map(|j| t.materials.texels[4 * i + j]);
            assert_eq!([unf(a[0]), unf(a[1]), unf(a[2])], m.base_color[..3]);
            assert_eq!((unf(a[3]), unf(b[3])), (m.metallic, m.roughness));
            assert_eq!(Vec3::new(unf(b[0]), unf(b[1]), unf(b[2])), m.emissive);
            let spec = Vec3::new(unf(d[0]), unf(d[1]), unf(d[2]));
            assert_eq!((spec, unf(d[3])), (m.specular_color, m.specular));
            assert_eq!(
                [c[0], c[1], c[2], c[3]],
                [
                    m.flags,
                    m.base_color_tex as u32,
                    m.emissive_tex as u32,
                    m.mr_tex as u32
                ]
            );
        }
        // The GpuLights, then one (zeroed) LightParams record: no punctual lights, no map.
        let records = LIGHT_PARAMS_TEXELS as usize;
        assert_eq!(t.lights.texels.len(), g.lights.len() + records);
        assert!(
            t.lights.texels[g.lights.len()..]
                .iter()
                .all(|x| *x == [0; 4])
        );
        assert_eq!(g.info.light_params_offset as usize, g.lights.len());
        for (l, x) in g.lights.iter().zip(&t.lights.texels) {
            assert_eq!(
                *x,
                [
                    l.triangle,
                    l.area.to_bits(),
                    l.pdf.to_bits(),
                    l.cdf.to_bits()
                ]
            );
        }
        assert!(!g.textures.is_empty() && !g.lights.is_empty());
        for (x, y) in g.textures.iter().zip(&t.textures.texels) {
            assert_eq!(*y, [x.offset, x.width, x.height, x.flags]);
        }
        for (k, w) in g.atlas.to_vec().iter().enumerate() {
            assert_eq!(t.texels.texels[k / 4][k % 4], *w);
        }
    }

    #[test]
    fn extents_wrap_rows_and_pad() {
        let a = array("a", vec![[1; 4]; SCENE_TEXELS_WIDTH as usize + 3]);
        assert_eq!(a.extent(), (SCENE_TEXELS_WIDTH, 2));
        let p = a.padded();
        assert_eq!(p.len(), 2 * SCENE_TEXELS_WIDTH as usize);
        assert_eq!(p[SCENE_TEXELS_WIDTH as usize + 2], [1; 4]);
        assert_eq!(p[SCENE_TEXELS_WIDTH as usize + 3], [0; 4]);
        let small = array("s", vec![]);
        assert_eq!((small.extent(), small.texels.len()), ((1, 1), 1));
        // Atlas words pack four to a texel, the last one zero-padded.
        let image = crate::scene::Image {
            name: None,
            width: 5,
            height: 1,
            rgba8: (1..=5u32).flat_map(u32::to_le_bytes).collect(),
        };
        let g = SceneGpu {
            atlas: Atlas::new(std::sync::Arc::new([image])),
            ..Default::default()
        };
        assert_eq!(g.texels().texels.texels, vec![[1, 2, 3, 4], [5, 0, 0, 0]]);
    }
}
