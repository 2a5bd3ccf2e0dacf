//! The `trace` pass: the path tracer's variants (`blueshift_layout::variants::TraceVariant`),
//! one frame's samples split into dispatches that stay under llvmpipe's loop limit, and the
//! guard that reports a frame which may have reached it.
use crate::buffers::SceneBuffers;
use crate::images::SceneImages;
use crate::{Result, TraceError};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, PipelineCache, Recorder, Res};
use blueshift_layout::params::{MASK_MODE_NONE, TRACE_GROUP_X, TRACE_GROUP_Y, TraceParams};
use blueshift_layout::variants::TraceVariant;
use blueshift_sampling::Sampler;

/// Path vertices (samples x (bounces + 1)) one trace dispatch runs per invocation in the
/// first frame. The samples of a dispatch run in one loop over path vertices (a lane whose
/// path ends starts its next sample, so the 8 SIMD lanes stay busy), and all their loop
/// iterations count against llvmpipe's limit of 65535 per SIMD batch, past which loops
/// silently exit. A path vertex costs about 30..60 loop iterations in the bundled scenes, a
/// few hundred at worst in large meshes, so 64 vertices stay well below the limit; later
/// frames size their dispatches from the counted iterations ([`next_dispatch_vertices`]).
pub const TRACE_FIRST_DISPATCH_VERTICES: u32 = 64;
/// Bounds of the adaptive dispatch size, in path vertices.
pub const TRACE_MAX_DISPATCH_VERTICES: u32 = 1024;
/// Counted loop iterations per batch a dispatch is sized for: well under the guard, so that
/// a frame costlier than the last (a camera move) still stays below it.
pub const TRACE_DISPATCH_ITERATIONS: u32 = 16_000;

/// llvmpipe ends every loop of a SIMD batch silently once the batch has run 65535 loop
/// iterations in total (one counter shared by all loops of an invocation).
pub const LLVMPIPE_LOOP_LIMIT: u32 = 65535;

/// Default loop guard (`RenderConfig::loop_guard` of the renderer): the trace shader counts its batches' loop
/// iterations (trace_body.glsl) and the renderer reports a frame whose count reaches this as
/// an error, since its paths may have been cut short. The count undercounts a batch by up to
/// ~1.5x (trace_body.glsl), hence 40000 of 65535.
pub const TRACE_LOOP_GUARD: u32 = 40_000;

/// Samples per trace dispatch of `vertices` path vertices for paths of up to `bounces + 1`
/// vertices (at least one).
pub fn samples_per_dispatch(vertices: u32, bounces: u32) -> u32 {
    (vertices / (bounces + 1)).max(1)
}

/// The dispatch size (path vertices) for the next frame, after a frame whose dispatches of
/// `samples` samples each counted `iterations` loop iterations in their costliest batch:
/// [`TRACE_DISPATCH_ITERATIONS`] at the same cost per vertex.
pub fn next_dispatch_vertices(samples: u32, bounces: u32, iterations: u32) -> u32 {
    let used = samples.max(1) as u64 * (bounces as u64 + 1);
    let per_vertex = (iterations as u64).div_ceil(used).max(1);
    (TRACE_DISPATCH_ITERATIONS as u64 / per_vertex).clamp(
        TRACE_FIRST_DISPATCH_VERTICES as u64,
        TRACE_MAX_DISPATCH_VERTICES as u64,
    ) as u32
}

/// The variant for these push constants over these scene images: llvmpipe executes both
/// sides of every branch, so each variant compiles out what the method and scene never use.
/// (With loop statistics, one shader serves every mask, texture and BRDF choice.)
pub fn trace_variant(
    p: &TraceParams,
    scene: &SceneImages,
    loop_stats: bool,
) -> Result<TraceVariant> {
    let sampler = Sampler::ALL
        .into_iter()
        .find(|&s| s as u32 == p.sampler_kind)
        .ok_or_else(|| TraceError::Invalid(format!("sampler kind {}", p.sampler_kind)))?;
    let v = TraceVariant {
        sampler,
        mask: p.mask_mode != MASK_MODE_NONE,
        textures: scene.textured,
        lambert: scene.lambert,
        lights: scene.punctual_or_map,
        loop_stats,
    };
    Ok(v.canonical())
}

/// A frame whose trace pass counted `iterations` loop iterations in its costliest SIMD batch
/// is an error at `guard` and above: its paths may have been cut short.
pub fn check_loop_guard(iterations: u32, guard: u32) -> Result<()> {
    if iterations >= guard {
        return Err(TraceError::LoopLimit { iterations, guard });
    }
    Ok(())
}

/// The path tracer's pipelines, created as frames first need them.
pub struct TracePass {
    dev: Device,
    pipelines: PipelineCache<TraceVariant>,
}

impl std::fmt::Debug for TracePass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TracePass").finish_non_exhaustive()
    }
}

/// The scene's resources by name (shared by the path tracer and `gbuffer`).
pub(crate) fn scene_resources<'a>(
    s: &'a SceneBuffers,
    i: &'a SceneImages,
) -> [(&'static str, Res<'a>); 8] {
    [
        ("scene_nodes", (&i.nodes).into()),
        ("scene_triangles", (&i.triangles).into()),
        ("scene_shading", (&i.shading).into()),
        ("scene_materials", (&i.materials).into()),
        ("scene_textures", (&i.textures).into()),
        ("scene_texels", (&i.texels).into()),
        ("scene_lights", (&i.lights).into()),
        ("scene", (&s.info).into()),
    ]
}

/// Bindings of every path-tracer variant (and of the all-runtime `trace/trace`); the mask
/// variants add [`MASK_TRACE_BINDING`].
pub const TRACE_BINDINGS: [Binding; 13] = [
    Binding::image(0, "scene_nodes"),
    Binding::image(1, "scene_triangles"),
    Binding::image(2, "scene_shading"),
    Binding::image(3, "scene_materials"),
    Binding::image(4, "scene_textures"),
    Binding::image(5, "scene_texels"),
    Binding::image(6, "scene_lights"),
    Binding::storage(7, "scene"),
    Binding::storage(8, "seeds"),
    Binding::storage(9, "mask"),
    Binding::storage(10, "estimate"),
    Binding::storage(11, "trace_status"),
    Binding::storage(12, "hbo19_keys"),
];
/// The mask variants' per-pixel flags of the primary hit (`TRACE_FLAG_SEED_JITTER_ON_TEXTURES`).
pub const MASK_TRACE_BINDING: Binding = Binding::storage(13, "primary_flags");

/// The bindings of `variant`.
pub fn trace_bindings(variant: &TraceVariant) -> Vec<Binding> {
    let mut b = TRACE_BINDINGS.to_vec();
    if variant.mask {
        b.push(MASK_TRACE_BINDING);
    }
    b
}

impl TracePass {
    pub fn new(dev: &Device) -> Self {
        Self {
            dev: dev.clone(),
            pipelines: PipelineCache::default(),
        }
    }

    /// Records the path-tracing pass writing the raw estimate of this frame: one dispatch per
    /// [`samples_per_dispatch`]`(vertices, ..)` samples (see `TraceParams::sample_index`);
    /// returns the samples per dispatch.
    #[allow(clippy::too_many_arguments)]
    pub fn trace(
        &mut self,
        rec: &mut Recorder,
        p: &TraceParams,
        scene: &SceneBuffers,
        images: &SceneImages,
        seeds: &Buffer,
        mask: &Buffer,
        keys: &Buffer,
        estimate: &Buffer,
        primary_flags: &Buffer,
        status: &Buffer,
        vertices: u32,
        loop_stats: bool,
    ) -> Result<u32> {
        let variant = trace_variant(p, images, loop_stats)?;
        let dev = &self.dev;
        let pipeline = self.pipelines.get_or_create(variant, |v| {
            let push = size_of::<TraceParams>();
            blueshift_shaders::pipeline(dev, &v.shader(), &trace_bindings(&v), push)
        })?;
        let per_dispatch = samples_per_dispatch(vertices, p.max_bounces).min(p.spp);
        for first in (0..p.spp).step_by(per_dispatch as usize) {
            let p = TraceParams {
                sample_index: first,
                sample_count: per_dispatch.min(p.spp - first),
                ..*p
            };
            let bufs = [seeds, mask, estimate, status, keys, primary_flags];
            Self::trace_one(rec, pipeline, &p, scene, images, bufs, variant.mask)?;
        }
        Ok(per_dispatch)
    }

    fn trace_one(
        rec: &mut Recorder,
        pipeline: &ComputePipeline,
        p: &TraceParams,
        s: &SceneBuffers,
        i: &SceneImages,
        [seeds, mask, estimate, status, keys, primary_flags]: [&Buffer; 6],
        mask_variant: bool,
    ) -> Result<()> {
        let flags: &[(&str, Res)] = if mask_variant {
            &[("primary_flags", primary_flags.into())]
        } else {
            &[]
        };
        rec.dispatch(
            pipeline,
            &[
                &scene_resources(s, i)[..],
                &[
                    ("seeds", seeds.into()),
                    ("mask", mask.into()),
                    ("estimate", estimate.into()),
                    ("trace_status", status.into()),
                    ("hbo19_keys", keys.into()),
                ],
                flags,
            ]
            .concat(),
            bytemuck::bytes_of(p),
            [
                p.width.div_ceil(TRACE_GROUP_X),
                p.height.div_ceil(TRACE_GROUP_Y),
                1,
            ],
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dispatch_size_follows_the_counted_iterations() {
        // 8 samples of 8 vertices counted 2560 iterations: 40 per vertex -> 400 vertices.
        assert_eq!(next_dispatch_vertices(8, 7, 2560), 400);
        // Clamped to 64..=1024 path vertices; no count at all gives the maximum.
        assert_eq!(
            next_dispatch_vertices(8, 7, 60_000),
            TRACE_FIRST_DISPATCH_VERTICES
        );
        assert_eq!(next_dispatch_vertices(8, 7, 1), TRACE_MAX_DISPATCH_VERTICES);
        assert_eq!(next_dispatch_vertices(0, 0, 0), TRACE_MAX_DISPATCH_VERTICES);
        assert_eq!(samples_per_dispatch(400, 7), 50);
        assert_eq!(samples_per_dispatch(64, 100), 1);
    }

    #[test]
    fn every_variant_names_a_compiled_shader() {
        let names: Vec<&str> = blueshift_shaders::names().collect();
        for v in TraceVariant::all() {
            assert!(names.contains(&v.shader().as_str()), "{v:?}");
        }
    }
}
