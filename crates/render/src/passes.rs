//! The image passes: `trace/trace`, `trace/accumulate`, `trace/tonemap`.
use crate::upload::SceneBuffers;
use crate::Result;
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Recorder};
use blueshift_layout::params::{ImageParams, TraceParams};

pub struct ImagePasses {
    trace: ComputePipeline,
    accumulate: ComputePipeline,
    tonemap: ComputePipeline,
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

const TRACE_BINDINGS: [Binding; 11] = [
    Binding::storage(0, "bvh_nodes"),
    Binding::storage(1, "bvh_triangles"),
    Binding::storage(2, "triangle_shading"),
    Binding::storage(3, "materials"),
    Binding::storage(4, "textures"),
    Binding::storage(5, "texels"),
    Binding::storage(6, "lights"),
    Binding::storage(7, "scene_info"),
    Binding::storage(8, "seeds"),
    Binding::storage(9, "mask"),
    Binding::storage(10, "estimate"),
];

impl ImagePasses {
    pub fn new(dev: &Device) -> Result<Self> {
        let image = size_of::<ImageParams>();
        Ok(Self {
            trace: pipeline(
                dev,
                "trace/trace",
                &TRACE_BINDINGS,
                size_of::<TraceParams>(),
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

    /// Records the path-tracing pass writing the raw estimate of this frame: one dispatch per
    /// sample (see `TraceParams::sample_index`).
    pub fn trace(
        &self,
        rec: &mut Recorder,
        p: &TraceParams,
        scene: &SceneBuffers,
        seeds: &Buffer,
        mask: &Buffer,
        estimate: &Buffer,
    ) -> Result<()> {
        let s = scene;
        for sample in 0..p.spp {
            let p = TraceParams {
                sample_index: sample,
                ..*p
            };
            self.trace_one(rec, &p, s, seeds, mask, estimate)?;
        }
        Ok(())
    }

    fn trace_one(
        &self,
        rec: &mut Recorder,
        p: &TraceParams,
        s: &SceneBuffers,
        seeds: &Buffer,
        mask: &Buffer,
        estimate: &Buffer,
    ) -> Result<()> {
        rec.dispatch(
            &self.trace,
            &[
                (&s.nodes).into(),
                (&s.triangles).into(),
                (&s.shading).into(),
                (&s.materials).into(),
                (&s.textures).into(),
                (&s.texels).into(),
                (&s.lights).into(),
                (&s.info).into(),
                seeds.into(),
                mask.into(),
                estimate.into(),
            ],
            bytemuck::bytes_of(p),
            [p.width.div_ceil(8), p.height.div_ceil(8), 1],
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
