//! The GPU scene layout: every struct here is shared with GLSL through
//! `shaders/include/generated/scene.glsl` (see [`crate::glsl_header`]), read with
//! `layout(scalar)` so GLSL offsets equal the Rust ones.
//!
//! The arrays ([`SceneGpu`], sized as storage buffers by [`SceneGpu::buffer_sizes`]) and the
//! GLSL names of their storage-buffer form:
//!
//! | array              | element            | GLSL array name     | used by                |
//! |--------------------|--------------------|---------------------|------------------------|
//! | BVH nodes          | [`BvhNode`]        | `bvh_nodes[]`       | `bvh.glsl` (test shader) |
//! | BVH triangles      | [`GpuTriangle`]    | `bvh_triangles[]`   | `bvh.glsl` (test shader) |
//! | triangle shading   | [`TriangleShading`]| `triangle_shading[]`|                        |
//! | materials          | [`GpuMaterial`]    | `materials[]`       |                        |
//! | textures           | [`GpuTexture`]     | `textures[]`        |                        |
//! | texels             | `uint` (RGBA8, [`Atlas`]) | `texels[]`   |                        |
//! | lights             | [`GpuLight`]       | `lights[]`          |                        |
//!
//! Triangles, shading and lights are all in BVH leaf order: `Hit::triangle` indexes
//! `bvh_triangles[]` and `triangle_shading[]` alike.
//!
//! The path tracer reads the same arrays repacked as texels of storage images
//! ([`SceneGpu::texel_sources`], layout in the `texels` module), which lavapipe loads several
//! times faster than divergent storage-buffer elements.

mod atlas;
mod build;
mod lights;
mod quads;
mod texel_source;
mod texels;

pub use atlas::Atlas;
pub use build::SceneGpu;
pub use lights::EnvGpu;
pub use quads::{LIGHT_QUAD_SHIFT, LIGHT_TRIANGLE_MASK, QuadFrame};
pub use texel_source::TexelSource;
pub use texels::*;

use blueshift_layout::{Header, gpu_struct};
use glam::{Vec2, Vec3};

/// Traversal stack depth of `bvh.glsl`; the builder guarantees the tree is never deeper.
pub const BVH_STACK_SIZE: u32 = 64;
/// `Hit::triangle` of a miss.
pub const HIT_MISS: u32 = u32::MAX;
/// `GpuMaterial::flags`: the material is double sided (glTF `doubleSided`).
pub const MATERIAL_DOUBLE_SIDED: u32 = 1;
/// `GpuTexture::flags` bits 0..2: wrap mode along u (`TEXTURE_WRAP_*`).
pub const TEXTURE_WRAP_S_SHIFT: u32 = 0;
/// `GpuTexture::flags` bits 2..4: wrap mode along v.
pub const TEXTURE_WRAP_T_SHIFT: u32 = 2;
pub const TEXTURE_WRAP_REPEAT: u32 = 0;
pub const TEXTURE_WRAP_CLAMP: u32 = 1;
pub const TEXTURE_WRAP_MIRROR: u32 = 2;
/// `GpuTexture::flags`: magnification filter is NEAREST (else bilinear).
pub const TEXTURE_FILTER_NEAREST: u32 = 16;
/// `GpuLight::triangle` with this bit set: not a triangle; the low bits index the
/// [`LightParams`] records (punctual lights and the environment map).
pub const LIGHT_PARAMS_BIT: u32 = 0x8000_0000;
/// `LightParams::kind` values.
pub const LIGHT_POINT: u32 = 1;
pub const LIGHT_SPOT: u32 = 2;
pub const LIGHT_DIRECTIONAL: u32 = 3;
pub const LIGHT_ENVIRONMENT: u32 = 4;

gpu_struct! {
    /// One BVH node, 36 bytes. Nodes are flattened depth-first from the root at index 0, and
    /// the two children of an interior node are always adjacent.
    /// - interior (`count == 0`): children are `left_first` and `left_first + 1`;
    /// - leaf (`count > 0`): triangles `left_first .. left_first + count` of `bvh_triangles[]`.
    ///
    /// `skip` threads the tree for the stackless occlusion traversal: the node to visit after
    /// this one's subtree (the right sibling of a left child, else the parent's `skip`), 0 after
    /// the last (the root is never a skip target).
    pub struct BvhNode {
        pub aabb_min: Vec3,
        pub left_first: u32,
        pub aabb_max: Vec3,
        pub count: u32,
        pub skip: u32,
    }
}

impl BvhNode {
    /// A node with an empty box: no ray ever enters it (used to pad an empty buffer).
    pub const EMPTY: BvhNode = BvhNode {
        aabb_min: Vec3::splat(f32::MAX),
        left_first: 0,
        aabb_max: Vec3::splat(-f32::MAX),
        count: 0,
        skip: 0,
    };

    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }
}

gpu_struct! {
    /// Intersection data of one triangle (world space): vertex 0 and the two edges
    /// `e1 = v1 - v0`, `e2 = v2 - v0` that Möller–Trumbore needs. 36 bytes.
    pub struct GpuTriangle {
        pub v0: Vec3,
        pub e1: Vec3,
        pub e2: Vec3,
    }
}

gpu_struct! {
    /// Shading data of one triangle, parallel to `bvh_triangles[]`. Normals are world-space unit
    /// vectors (flat face normal where the file had none); `uv*` are TEXCOORD_0.
    /// Interpolate with the hit barycentrics: `(1-u-v)*x0 + u*x1 + v*x2`.
    /// `light` is this triangle's index in `lights[]`, or -1 if it does not emit.
    pub struct TriangleShading {
        pub n0: Vec3,
        pub n1: Vec3,
        pub n2: Vec3,
        pub uv0: Vec2,
        pub uv1: Vec2,
        pub uv2: Vec2,
        pub material: u32,
        pub light: i32,
    }
}

gpu_struct! {
    /// glTF metallic-roughness material. `base_color` is linear RGBA (the factor);
    /// `emissive` is the emissive factor times KHR_materials_emissive_strength (linear
    /// radiance). Texture fields index `textures[]`, -1 = none. Base color and emissive
    /// texels are sRGB-encoded, `mr_tex` is linear (G = roughness, B = metallic, as glTF).
    /// `specular` / `specular_color`: KHR_materials_specular factors (1 / white = plain glTF).
    pub struct GpuMaterial {
        pub base_color: [f32; 4],
        pub emissive: Vec3,
        pub metallic: f32,
        pub roughness: f32,
        pub base_color_tex: i32,
        pub emissive_tex: i32,
        pub mr_tex: i32,
        pub flags: u32,
        pub specular_color: Vec3,
        pub specular: f32,
    }
}

gpu_struct! {
    /// A texture: `width * height` RGBA8 texels starting at `texels[offset]`, row-major, top
    /// row first (glTF uv (0,0) is the top-left corner). A texel is packed as
    /// `r | g << 8 | b << 16 | a << 24`, i.e. `unpackUnorm4x8` order.
    /// `flags`: wrap modes and filter (`TEXTURE_*` constants).
    pub struct GpuTexture {
        pub offset: u32,
        pub width: u32,
        pub height: u32,
        pub flags: u32,
    }
}

gpu_struct! {
    /// One light for light sampling: an emissive triangle, or (`triangle` with
    /// [`LIGHT_PARAMS_BIT`]) a punctual light or the environment map. `pdf` is the probability
    /// of choosing it (power / total power; a triangle's power is luminance(emission) * area *
    /// pi, the others' in `build.rs`) and `cdf` the inclusive running sum (last entry exactly
    /// 1): pick the first light with `xi < cdf`. A triangle's area density is `pdf / area`.
    /// Two triangles that form a parallelogram are one light (`quads`): `triangle` holds the
    /// first one's index below [`LIGHT_QUAD_SHIFT`] and the quad's frame above, `area` both.
    pub struct GpuLight {
        pub triangle: u32,
        pub area: f32,
        pub pdf: f32,
        pub cdf: f32,
    }
}

gpu_struct! {
    /// Counts and scene-wide constants, for a uniform or push constant block.
    pub struct SceneInfo {
        pub triangle_count: u32,
        pub node_count: u32,
        pub material_count: u32,
        pub texture_count: u32,
        pub light_count: u32,
        pub texel_count: u32,
        pub total_light_power: f32,
        pub environment: Vec3,
        pub bounds_min: Vec3,
        pub bounds_max: Vec3,
        /// First texel of the [`LightParams`] records in the light image.
        pub light_params_offset: u32,
        /// First texel of the environment map's tables in the light image (see `texels`).
        pub env_offset: u32,
        /// Map size; 0 x 0 without a map (`environment` is then the constant radiance).
        pub env_width: u32,
        pub env_height: u32,
        /// The map's index among the lights (-1: next-event estimation does not sample it).
        pub env_light: i32,
        /// `(cos, sin)` of the map's rotation about +Y.
        pub env_rotation: Vec2,
    }
}

gpu_struct! {
    /// A light that is not a triangle (three texels): where it is, where it shines, how much.
    /// `kind` is a `LIGHT_*` value; cone cosines are (-2, -3) for all but spots (no falloff).
    pub struct LightParams {
        pub position: Vec3,
        pub kind: u32,
        pub direction: Vec3,
        pub cos_inner: f32,
        pub intensity: Vec3,
        pub cos_outer: f32,
    }
}

gpu_struct! {
    /// A ray segment: hits are accepted for `tmin <= t <= tmax`. `dir` need not be unit length
    /// (t is then in units of `dir`).
    pub struct Ray {
        pub origin: Vec3,
        pub tmin: f32,
        pub dir: Vec3,
        pub tmax: f32,
    }
}

gpu_struct! {
    /// A ray hit: distance, triangle (index into `bvh_triangles[]`), and the barycentrics of
    /// vertices 1 and 2. A miss has `triangle == HIT_MISS`, `t == ray.tmax`, `u == v == 0`.
    pub struct Hit {
        pub t: f32,
        pub triangle: u32,
        pub u: f32,
        pub v: f32,
    }
}

impl Ray {
    pub fn new(origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> Self {
        Ray {
            origin,
            tmin,
            dir,
            tmax,
        }
    }
}

impl Hit {
    /// The GPU encoding of a miss for `ray`.
    pub fn miss(ray: &Ray) -> Hit {
        Hit {
            t: ray.tmax,
            triangle: HIT_MISS,
            u: 0.0,
            v: 0.0,
        }
    }

    pub fn is_miss(&self) -> bool {
        self.triangle == HIT_MISS
    }

    /// Decodes a hit as written by `bvh_trace.comp`.
    pub fn from_gpu(raw: Hit) -> Option<Hit> {
        (!raw.is_miss()).then_some(raw)
    }
}

/// All shared structs and constants, in declaration order.
pub(crate) fn header() -> Header {
    Header::new()
        .constant("BVH_STACK_SIZE", BVH_STACK_SIZE)
        .constant("HIT_MISS", HIT_MISS)
        .constant("MATERIAL_DOUBLE_SIDED", MATERIAL_DOUBLE_SIDED)
        .constant("TEXTURE_WRAP_S_SHIFT", TEXTURE_WRAP_S_SHIFT)
        .constant("TEXTURE_WRAP_T_SHIFT", TEXTURE_WRAP_T_SHIFT)
        .constant("TEXTURE_WRAP_REPEAT", TEXTURE_WRAP_REPEAT)
        .constant("TEXTURE_WRAP_CLAMP", TEXTURE_WRAP_CLAMP)
        .constant("TEXTURE_WRAP_MIRROR", TEXTURE_WRAP_MIRROR)
        .constant("TEXTURE_FILTER_NEAREST", TEXTURE_FILTER_NEAREST)
        .constant("LIGHT_PARAMS_BIT", LIGHT_PARAMS_BIT)
        .constant("LIGHT_QUAD_SHIFT", LIGHT_QUAD_SHIFT)
        .constant("LIGHT_TRIANGLE_MASK", LIGHT_TRIANGLE_MASK)
        .constant("LIGHT_POINT", LIGHT_POINT)
        .constant("LIGHT_SPOT", LIGHT_SPOT)
        .constant("LIGHT_DIRECTIONAL", LIGHT_DIRECTIONAL)
        .constant("LIGHT_ENVIRONMENT", LIGHT_ENVIRONMENT)
        .constant("SCENE_TEXELS_WIDTH_LOG2", SCENE_TEXELS_WIDTH_LOG2)
        .constant("NODE_TEXELS", NODE_TEXELS)
        .constant("NODE_COUNT_BITS", NODE_COUNT_BITS)
        .constant("TRIANGLE_TEXELS", TRIANGLE_TEXELS)
        .constant("SHADING_TEXELS", SHADING_TEXELS)
        .constant("MATERIAL_TEXELS", MATERIAL_TEXELS)
        .constant("LIGHT_TEXELS", LIGHT_TEXELS)
        .constant("TEXTURE_TEXELS", TEXTURE_TEXELS)
        .constant("LIGHT_PARAMS_TEXELS", LIGHT_PARAMS_TEXELS)
        .constant("ATLAS_WORDS_PER_TEXEL", ATLAS_WORDS_PER_TEXEL)
        .push::<BvhNode>()
        .push::<GpuTriangle>()
        .push::<TriangleShading>()
        .push::<GpuMaterial>()
        .push::<GpuTexture>()
        .push::<GpuLight>()
        .push::<LightParams>()
        .push::<SceneInfo>()
        .push::<Ray>()
        .push::<Hit>()
}

// Sizes the GLSL side relies on.
const _: () = {
    assert!(size_of::<BvhNode>() == 36);
    assert!(size_of::<GpuTriangle>() == 36);
    assert!(size_of::<TriangleShading>() == 68);
    assert!(size_of::<GpuMaterial>() == 68);
    assert!(size_of::<GpuTexture>() == 16);
    assert!(size_of::<GpuLight>() == 16);
    assert!(size_of::<LightParams>() == 16 * LIGHT_PARAMS_TEXELS as usize);
    assert!(size_of::<Ray>() == 32);
    assert!(size_of::<Hit>() == 16);
};

#[cfg(test)]
mod tests {
    use super::*;
    use blueshift_layout::GpuStruct;

    #[test]
    fn header_lists_every_struct() {
        let h = crate::glsl_header();
        for name in [
            BvhNode::NAME,
            GpuTriangle::NAME,
            TriangleShading::NAME,
            GpuMaterial::NAME,
            GpuTexture::NAME,
            GpuLight::NAME,
            LightParams::NAME,
            SceneInfo::NAME,
            Ray::NAME,
            Hit::NAME,
        ] {
            assert!(h.contains(&format!("struct {name} {{")), "{name} missing");
        }
        assert!(h.contains("const uint BVH_STACK_SIZE = 64u;"));
        assert!(h.contains("#ifndef GENERATED_SCENE_GLSL"));
    }
}
