//! The renderers the viewer drives: the views (accumulating along the motion while the
//! camera moves, the running mean while it is still) and the error view's reference.
use super::controls::{REFERENCE_SPP, Settings};
use super::gpu::Options;
use anyhow::{Context, Result};
use blueshift_device::Device;
use blueshift_render::{Accumulation, Method, RenderConfig, Renderer};

pub fn make_renderer(
    dev: &Device,
    opts: &Options,
    size: (u32, u32),
    s: &Settings,
    method: Method,
) -> Result<Renderer> {
    // What one sees while flying is what `eval` measures (the TAA); a still view converges.
    let cfg = RenderConfig {
        method,
        accumulation: Accumulation::Follow,
        ..opts.template.clone()
    };
    start(dev, opts, sized(cfg, size, s))
}

/// The error view's reference: Sobol, accumulating while the camera is still.
pub fn make_reference(
    dev: &Device,
    opts: &Options,
    size: (u32, u32),
    s: &Settings,
) -> Result<Renderer> {
    let s = Settings {
        spp: s.spp.max(REFERENCE_SPP),
        ..s.clone()
    };
    // Sobol's own sampler, whatever `--sampler` gives the views.
    let cfg = RenderConfig {
        method: Method::Sobol,
        sampler: None,
        ..opts.template.clone()
    };
    start(dev, opts, sized(cfg, size, &s))
}

/// `cfg` at `size` with the quality settings of `s`.
fn sized(cfg: RenderConfig, size: (u32, u32), s: &Settings) -> RenderConfig {
    RenderConfig {
        width: size.0,
        height: size.1,
        spp: s.spp,
        bounces: s.bounces,
        block: s.block_for(cfg.method),
        ..cfg
    }
}

fn start(dev: &Device, opts: &Options, cfg: RenderConfig) -> Result<Renderer> {
    let (method, w, h) = (cfg.method, cfg.width, cfg.height);
    Renderer::new(dev, &opts.scene, &opts.assets, cfg)
        .with_context(|| format!("creating the {method} renderer at {w}x{h}"))
}
