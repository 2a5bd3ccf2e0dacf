//! The GPU test harness ("GLSL shader unit runs"): a device on lavapipe (or any Vulkan device)
//! with the Khronos validation layer on; running a compute shader and reading results back;
//! and a check on drop that validation reported nothing, so every GPU test fails on any message.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use blueshift_device::{
    Binding, Buffer, ComputePipeline, Device, Instance, InstanceDesc, MemoryLocation, PassTime,
    Recorder, Res,
};

#[cfg(test)]
mod adaptive;
#[cfg(test)]
mod anchors;
#[cfg(test)]
mod bindings;
#[cfg(test)]
mod blue;
#[cfg(test)]
mod bvh;
#[cfg(test)]
mod cycle;
#[cfg(test)]
mod default_quality;
#[cfg(test)]
mod demod;
#[cfg(test)]
mod follow;
#[cfg(test)]
mod frame_memory;
#[cfg(test)]
mod hbo19;
#[cfg(test)]
mod headers;
#[cfg(test)]
mod history;
#[cfg(test)]
mod jitter;
#[cfg(test)]
mod light_quads;
#[cfg(test)]
mod lights;
#[cfg(test)]
mod lights_twin;
#[cfg(test)]
mod loop_stats;
#[cfg(test)]
mod mask_shift;
#[cfg(test)]
mod motion;
#[cfg(test)]
mod pairs_gate;
#[cfg(test)]
mod permute;
#[cfg(test)]
mod recipes;
#[cfg(test)]
mod rng;
#[cfg(test)]
mod sampling;
#[cfg(test)]
mod sort_variants;
#[cfg(test)]
mod still_volume;
#[cfg(test)]
mod taa;
#[cfg(test)]
mod trace;

/// Whether two RGBA images are equal bit for bit.
pub fn same_bits(a: &[[f32; 4]], b: &[[f32; 4]]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| p.map(f32::to_bits) == q.map(f32::to_bits))
}

/// Pairs of pixels of one 8x8 block of a `w x h` screen out of order: `at(x, y)` gives a
/// pixel's (mask rank, sample key), and a pair is out of order when the lower rank holds the
/// higher key.
pub fn pairs_out_of_order(w: u32, h: u32, at: impl Fn(u32, u32) -> (u32, f32)) -> usize {
    let mut bad = 0;
    for (bx, by) in (0..w.div_ceil(8)).flat_map(|bx| (0..h.div_ceil(8)).map(move |by| (bx, by))) {
        let px: Vec<(u32, f32)> = (0..64)
            .map(|i| (bx * 8 + i % 8, by * 8 + i / 8))
            .filter(|&(x, y)| x < w && y < h)
            .map(|(x, y)| at(x, y))
            .collect();
        for a in &px {
            bad += px.iter().filter(|b| a.0 < b.0 && a.1 > b.1).count();
        }
    }
    bad
}

/// Serialises creating and destroying instances and devices across the test threads (the
/// tests themselves still run in parallel). The loader, the validation layer and lavapipe keep
/// process-wide state there; a cold CI run once died with SIGSEGV while tests were creating
/// and dropping devices in parallel (not reproduced in dozens of reruns), and this rules races
/// in those calls out.
static LIFECYCLE: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn lifecycle() -> std::sync::MutexGuard<'static, ()> {
    // A test that panicked while holding it poisons nothing the next one needs.
    LIFECYCLE.lock().unwrap_or_else(|e| e.into_inner())
}

/// A validated device plus a recorder. Panics on drop if validation reported anything.
pub struct Gpu {
    instance: Option<Instance>,
    pub dev: Option<Device>,
    pub rec: Option<Recorder>,
}

impl Gpu {
    /// Creates the device with validation on. Panics with the device layer's message (which
    /// names the apt package to install) when there is no Vulkan device or no validation layer.
    pub fn new() -> Self {
        let _lock = lifecycle();
        let instance = Instance::new(&InstanceDesc {
            validation: true,
            extensions: vec![],
        })
        .unwrap_or_else(|e| panic!("GPU tests need Vulkan with validation: {e}"));
        let dev = Device::new(&instance, &Default::default())
            .unwrap_or_else(|e| panic!("GPU tests need a Vulkan device: {e}"));
        let rec = Recorder::new(&dev, "test").expect("recorder");
        Self {
            instance: Some(instance),
            dev: Some(dev),
            rec: Some(rec),
        }
    }

    pub fn dev(&self) -> &Device {
        self.dev.as_ref().expect("device alive")
    }

    /// A pipeline for shader `name` with the given declared bindings and push size.
    pub fn pipeline(&self, name: &str, bindings: &[Binding], push_size: u32) -> ComputePipeline {
        let spirv = blueshift_shaders::require(name).unwrap();
        ComputePipeline::new(self.dev(), name, &spirv, bindings, push_size).unwrap()
    }

    /// A zeroed host-readable buffer of `n` elements of `T`.
    pub fn output<T: bytemuck::Pod>(&self, name: &str, n: usize) -> Buffer {
        Buffer::new(
            self.dev(),
            name,
            (n * std::mem::size_of::<T>()) as u64,
            MemoryLocation::GpuToCpu,
        )
        .unwrap()
    }

    /// Records one dispatch in its own pass, submits and waits.
    pub fn run(
        &mut self,
        pipeline: &ComputePipeline,
        resources: &[(&str, Res<'_>)],
        push: &[u8],
        groups: [u32; 3],
    ) -> Vec<PassTime> {
        let rec = self.rec.as_mut().expect("recorder alive");
        rec.begin().unwrap();
        rec.begin_pass(&pipeline.name).unwrap();
        rec.dispatch(pipeline, resources, push, groups).unwrap();
        rec.submit_and_wait().unwrap()
    }
}

impl Default for Gpu {
    fn default() -> Self {
        Self::new()
    }
}

impl Drop for Gpu {
    fn drop(&mut self) {
        let lock = lifecycle();
        self.rec.take();
        self.dev.take();
        let msgs = self
            .instance
            .take()
            .map(|i| i.validation_log().messages())
            .unwrap_or_default();
        drop(lock);
        if !msgs.is_empty() && !std::thread::panicking() {
            panic!("{} validation message(s):\n{}", msgs.len(), msgs.join("\n"));
        }
    }
}

/// A small deterministic generator for test inputs (64-bit LCG, high bits out).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next_u32(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) as u32
    }
    /// Uniform in [0, 1) with 24 bits.
    pub fn unit(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 / (1u32 << 24) as f32
    }
    /// A random permutation of 0..n.
    pub fn perm(&mut self, n: u32) -> Vec<u32> {
        let mut m: Vec<u32> = (0..n).collect();
        for i in (1..m.len()).rev() {
            m.swap(i, self.next_u32() as usize % (i + 1));
        }
        m
    }
    /// History means as `history_key` leaves them: NaN (rank against the class mean) for a
    /// quarter of the `n` pixels, the others small keys in steps of 0.5 (ties) plus a bias.
    pub fn history_means(&mut self, n: usize, steps: u32) -> Vec<f32> {
        (0..n)
            .map(|_| match self.next_u32() % 4 {
                0 => f32::NAN,
                r => (self.next_u32() % steps) as f32 * 0.5 + r as f32 * 0.1,
            })
            .collect()
    }
}

/// Luminance of a converged Cornell-box image at `w x w` (Owen-Sobol, 512 spp, direct light,
/// pixel-centre rays): the reference the end-to-end error tests measure against.
pub fn cornell_reference(
    gpu: &Gpu,
    scene: &blueshift_scene::Scene,
    assets: &blueshift_render::MethodAssets,
    w: u32,
) -> Vec<f32> {
    use blueshift_render::{Method, RenderConfig, Renderer};
    let cfg = RenderConfig {
        spp: 128,
        bounces: 1,
        method: Method::Sobol,
        no_jitter: true,
        ..RenderConfig::new(w, w)
    };
    let mut r = Renderer::new(gpu.dev(), scene, assets, cfg).unwrap();
    for _ in 0..4 {
        r.render_frame().unwrap();
    }
    r.read_accum().unwrap().iter().map(|p| p[3]).collect()
}

/// Workgroup count covering `n` invocations at `local` per group.
pub fn groups_for(n: u32, local: u32) -> u32 {
    n.div_ceil(local)
}
