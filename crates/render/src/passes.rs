//! The image passes: the path tracer (`trace/variants/*`), `trace/accumulate`,
//! `trace/tonemap`, and `trace/upload_texels` (scene images, once per scene).
use crate::images::SceneImages;
use crate::upload::SceneBuffers;
use crate::{RenderError, Result};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Image, Recorder, Res};
use blueshift_layout::params::{
    ImageParams, MASK_MODE_NONE, TRACE_GROUP_X, TRACE_GROUP_Y, TraceParams,
};
use blueshift_sampling::Sampler;

pub struct ImagePasses {
    dev: Device,
    /// Path-tracer variants created so far.
    trace: Vec<(TraceVariant, ComputePipeline)>,
    accumulate: ComputePipeline,
    tonemap: ComputePipeline,
    upload: ComputePipeline,
}

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

/// Default [`crate::RenderConfig::loop_guard`]: the trace shader counts its batches' loop
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

/// Which path-tracer pipeline a frame needs. llvmpipe executes both sides of every branch,
/// so each variant compiles out what the method and scene never use (trace_body.glsl); all
/// variants share one binding table and push-constant block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TraceVariant {
    pub sampler: Sampler,
    /// Blue-noise mask modes (`TraceParams::mask_mode != MASK_MODE_NONE`).
    pub mask: bool,
    /// Material textures (any material has one).
    pub textures: bool,
    /// The Lambert-only BRDF (every material has metallic = specular = 0).
    pub lambert: bool,
    /// Count loop iterations (`trace/trace_loop_stats*`, every choice made at run time, so the
    /// other fields but the sampler do not apply; same paths as the other variants).
    pub loop_stats: bool,
}

impl TraceVariant {
    /// The variant for these push constants over these scene images.
    pub fn of(p: &TraceParams, scene: &SceneImages, loop_stats: bool) -> Result<Self> {
        let sampler = Sampler::ALL
            .into_iter()
            .find(|&s| s as u32 == p.sampler_kind)
            .ok_or_else(|| RenderError::Invalid(format!("sampler kind {}", p.sampler_kind)))?;
        Ok(Self {
            sampler,
            mask: p.mask_mode != MASK_MODE_NONE,
            textures: scene.textured,
            lambert: scene.lambert,
            loop_stats,
        })
    }

    /// The shader name, `trace/variants/<sampler>[_mask][_tex][_lambert]`, or with loop
    /// statistics `trace/trace_loop_stats[_hbo19]`.
    pub fn shader(self) -> String {
        let flag = |on: bool, suffix: &'static str| if on { suffix } else { "" };
        if self.loop_stats {
            let hbo19 = self.sampler == Sampler::Hbo19;
            return format!("trace/trace_loop_stats{}", flag(hbo19, "_hbo19"));
        }
        format!(
            "trace/variants/{}{}{}{}",
            self.sampler.name(),
            flag(self.mask, "_mask"),
            flag(self.textures, "_tex"),
            flag(self.lambert, "_lambert"),
        )
    }
}

impl std::fmt::Debug for ImagePasses {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ImagePasses").finish_non_exhaustive()
    }
}

fn pipeline(
    dev: &Device,
    name: &str,
    bindings: &[Binding],
    push: usize,
) -> Result<ComputePipeline> {
    Ok(blueshift_shaders::pipeline(dev, name, bindings, push)?)
}

/// The scene's resources in binding order 0-7 (shared by the path tracer and `gbuffer`).
pub(crate) fn scene_resources<'a>(s: &'a SceneBuffers, i: &'a SceneImages) -> [Res<'a>; 8] {
    [
        (&i.nodes).into(),
        (&i.triangles).into(),
        (&i.shading).into(),
        (&i.materials).into(),
        (&i.textures).into(),
        (&i.texels).into(),
        (&i.lights).into(),
        (&s.info).into(),
    ]
}

/// Bindings of every path-tracer variant (and of the all-runtime `trace/trace`).
pub const TRACE_BINDINGS: [Binding; 13] = [
    Binding::image(0, "scene_nodes"),
    Binding::image(1, "scene_triangles"),
    Binding::image(2, "scene_shading"),
    Binding::image(3, "scene_materials"),
    Binding::image(4, "scene_textures"),
    Binding::image(5, "scene_texels"),
    Binding::image(6, "scene_lights"),
    Binding::storage(7, "scene_info"),
    Binding::storage(8, "seeds"),
    Binding::storage(9, "mask"),
    Binding::storage(10, "estimate"),
    Binding::storage(11, "trace_status"),
    Binding::storage(12, "hbo19_keys"),
];

impl ImagePasses {
    pub fn new(dev: &Device) -> Result<Self> {
        let image = size_of::<ImageParams>();
        Ok(Self {
            dev: dev.clone(),
            trace: Vec::new(),
            upload: pipeline(
                dev,
                "trace/upload_texels",
                &[Binding::storage(0, "src"), Binding::image(1, "dst")],
                4,
            )?,
            accumulate: pipeline(
                dev,
                "trace/accumulate",
                &[
                    Binding::storage(0, "estimate"),
                    Binding::storage(1, "accum"),
                ],
                image,
            )?,
            tonemap: pipeline(
                dev,
                "trace/tonemap",
                &[Binding::storage(0, "source"), Binding::storage(1, "ldr")],
                image,
            )?,
        })
    }

    /// The path-tracer pipeline of `variant`, created on first use (lavapipe compiles a
    /// pipeline on its first dispatch, so unused variants cost nothing).
    fn trace_pipeline(&mut self, variant: TraceVariant) -> Result<&ComputePipeline> {
        let i = match self.trace.iter().position(|(v, _)| *v == variant) {
            Some(i) => i,
            None => {
                let name = variant.shader();
                let p = pipeline(&self.dev, &name, &TRACE_BINDINGS, size_of::<TraceParams>())?;
                self.trace.push((variant, p));
                self.trace.len() - 1
            }
        };
        Ok(&self.trace[i].1)
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
        status: &Buffer,
        vertices: u32,
        loop_stats: bool,
    ) -> Result<u32> {
        let variant = TraceVariant::of(p, images, loop_stats)?;
        let pipeline = self.trace_pipeline(variant)?;
        let per_dispatch = samples_per_dispatch(vertices, p.max_bounces).min(p.spp);
        for first in (0..p.spp).step_by(per_dispatch as usize) {
            let p = TraceParams {
                sample_index: first,
                sample_count: per_dispatch.min(p.spp - first),
                ..*p
            };
            let bufs = [seeds, mask, estimate, status, keys];
            Self::trace_one(rec, pipeline, &p, scene, images, bufs)?;
        }
        Ok(per_dispatch)
    }

    fn trace_one(
        rec: &mut Recorder,
        pipeline: &ComputePipeline,
        p: &TraceParams,
        s: &SceneBuffers,
        i: &SceneImages,
        [seeds, mask, estimate, status, keys]: [&Buffer; 5],
    ) -> Result<()> {
        rec.dispatch(
            pipeline,
            &[
                &scene_resources(s, i)[..],
                &[
                    seeds.into(),
                    mask.into(),
                    estimate.into(),
                    status.into(),
                    keys.into(),
                ],
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

    /// Records the copy of `count` texels from `src` into the scene image `dst`.
    pub fn upload_texels(
        &self,
        rec: &mut Recorder,
        src: &Buffer,
        dst: &Image,
        count: u32,
    ) -> Result<()> {
        let groups = count.div_ceil(64);
        let x = groups.min(self.dev.info().max_compute_work_group_count[0]);
        rec.dispatch(
            &self.upload,
            &[src.into(), dst.into()],
            bytemuck::bytes_of(&count),
            [x, groups.div_ceil(x), 1],
        )?;
        Ok(())
    }

    /// Records the running-mean accumulation.
    pub fn accumulate(
        &self,
        rec: &mut Recorder,
        p: &ImageParams,
        estimate: &Buffer,
        accum: &Buffer,
    ) -> Result<()> {
        let groups = [(p.width * p.height).div_ceil(64), 1, 1];
        rec.dispatch(
            &self.accumulate,
            &[estimate.into(), accum.into()],
            bytemuck::bytes_of(p),
            groups,
        )?;
        Ok(())
    }

    /// Records the sRGB tonemap of `source` into packed RGBA8.
    pub fn tonemap(
        &self,
        rec: &mut Recorder,
        p: &ImageParams,
        source: &Buffer,
        ldr: &Buffer,
    ) -> Result<()> {
        let groups = [(p.width * p.height).div_ceil(64), 1, 1];
        rec.dispatch(
            &self.tonemap,
            &[source.into(), ldr.into()],
            bytemuck::bytes_of(p),
            groups,
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
        for sampler in Sampler::ALL {
            for bits in 0..16 {
                let v = TraceVariant {
                    sampler,
                    mask: bits & 1 != 0,
                    textures: bits & 2 != 0,
                    lambert: bits & 4 != 0,
                    loop_stats: bits & 8 != 0,
                };
                assert!(names.contains(&v.shader().as_str()), "{v:?}");
            }
        }
    }
}
