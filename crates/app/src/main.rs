//! `blueshift`: the command-line entry point.
mod args;
mod bench;
mod eval;
mod fail;
mod info;
mod lighting;
mod output;
mod render;
mod soak;
mod view;

use clap::{Parser, Subcommand};

/// Blueshift: a path tracer whose noise is blue in screen space and stays blue over time.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Cli {
    /// Enable VK_LAYER_KHRONOS_validation (also: BLUESHIFT_VALIDATION=1).
    #[arg(long, global = true)]
    validation: bool,
    /// Use this Vulkan device (index as printed by `blueshift info`; also BLUESHIFT_DEVICE_INDEX).
    #[arg(long, global = true)]
    device_index: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print the device, driver, limits and features, and verify a compute dispatch.
    Info(info::InfoArgs),
    /// Render frames of a scene headless to PNG (tonemapped) and EXR (linear raw estimate).
    Render(render::RenderArgs),
    /// Compare methods against references and write report.md/report.json/figures.
    Eval(eval::EvalArgs),
    /// Throughput of the path tracer (Msamples/s, Mrays/s) from GPU timestamps.
    Bench(bench::BenchArgs),
    /// Long run of the frame loop checking the seed permutation and flat host/device memory.
    Soak(soak::SoakArgs),
    /// Desktop demo: a window with a fly camera, method switching and split-screen.
    View(view::ViewArgs),
}

/// Exit codes: 0 success, 1 any error (one `error: ...` line, usage errors included),
/// 2 internal error (a panic: a bug, never a reaction to bad input).
fn main() -> std::process::ExitCode {
    fail::install_panic_hook();
    let cli: Cli = match fail::parse() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    fail::run(|| match &cli.command {
        Command::Info(args) => info::run(&cli_gpu(&cli), args),
        Command::Render(args) => render::run(&cli_gpu(&cli), args),
        Command::Eval(args) => eval::run(&cli_gpu(&cli), args),
        Command::Bench(args) => bench::run(&cli_gpu(&cli), args),
        Command::Soak(args) => soak::run(&cli_gpu(&cli), args),
        Command::View(args) => view::run(&cli_gpu(&cli), args),
    })
}

/// Device options shared by every subcommand.
#[derive(Debug, Clone, Copy)]
pub struct GpuOpts {
    pub validation: bool,
    pub device_index: Option<usize>,
}

fn cli_gpu(cli: &Cli) -> GpuOpts {
    GpuOpts {
        validation: cli.validation,
        device_index: cli.device_index,
    }
}

impl GpuOpts {
    /// A headless device with these options.
    pub fn device(&self) -> anyhow::Result<blueshift_device::Device> {
        Ok(blueshift_device::headless(
            self.validation,
            self.device_index,
        )?)
    }
}

/// Fails if validation (when on) reported anything.
pub fn check_validation(dev: &blueshift_device::Device) -> anyhow::Result<()> {
    let msgs = dev.validation_messages();
    if !msgs.is_empty() {
        anyhow::bail!("{} validation message(s), first: {}", msgs.len(), msgs[0]);
    }
    Ok(())
}
