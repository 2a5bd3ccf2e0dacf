//! The image passes after the trace: `image/accumulate` (running mean) and `image/tonemap`
//! (exposure, sRGB, packed RGBA8).
use crate::Result;
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Recorder};
use blueshift_layout::params::ImageParams;

pub struct ImagePasses {
    accumulate: ComputePipeline,
    tonemap: ComputePipeline,
}

impl std::fmt::Debug for ImagePasses {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ImagePasses").finish_non_exhaustive()
    }
}

impl ImagePasses {
    pub fn new(dev: &Device) -> Result<Self> {
        let push = size_of::<ImageParams>();
        let pipeline = |name: &str, a: &'static str, b: &'static str| {
            let bindings = [Binding::storage(0, a), Binding::storage(1, b)];
            blueshift_shaders::pipeline(dev, name, &bindings, push)
        };
        Ok(Self {
            accumulate: pipeline("image/accumulate", "estimate", "accum")?,
            tonemap: pipeline("image/tonemap", "source", "ldr")?,
        })
    }

    /// Records the running-mean accumulation of `estimate` into `accum`.
    pub fn accumulate(
        &self,
        rec: &mut Recorder,
        p: &ImageParams,
        estimate: &Buffer,
        accum: &Buffer,
    ) -> Result<()> {
        per_pixel(
            rec,
            &self.accumulate,
            p,
            [("estimate", estimate), ("accum", accum)],
        )
    }

    /// Records the sRGB tonemap of `source` into packed RGBA8.
    pub fn tonemap(
        &self,
        rec: &mut Recorder,
        p: &ImageParams,
        source: &Buffer,
        ldr: &Buffer,
    ) -> Result<()> {
        per_pixel(rec, &self.tonemap, p, [("source", source), ("ldr", ldr)])
    }
}

/// Dispatches `pipeline` over `p`'s pixels, one invocation each (64 per workgroup).
fn per_pixel(
    rec: &mut Recorder,
    pipeline: &ComputePipeline,
    p: &ImageParams,
    [a, b]: [(&str, &Buffer); 2],
) -> Result<()> {
    rec.dispatch(
        pipeline,
        &[(a.0, a.1.into()), (b.0, b.1.into())],
        bytemuck::bytes_of(p),
        [(p.width * p.height).div_ceil(64), 1, 1],
    )?;
    Ok(())
}
