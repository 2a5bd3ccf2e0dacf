//! The paper's permutation in an engine's frame loop, using only `blueshift-permute`'s public
//! API. A stand-in compute shader (`shaders/example/estimate_from_seeds.comp`) plays the
//! engine's renderer: it reads each pixel's seed and writes an estimate whose `.w` is the
//! sorting key. The sorting pass then ranks every 4x4 block against the frame's mask and
//! retargets the seeds into the other buffer, ready for the next frame. Every frame is checked
//! against the CPU twins, as a port of the passes to another engine would be.
//!
//! `cargo run -p blueshift-permute --example engine -- [WIDTH HEIGHT FRAMES]`
use blueshift_assets::{MethodAssets, default_assets_dir};
use blueshift_device::{Binding, Buffer, Device, Instance, InstanceDesc, MemoryLocation, Recorder};
use blueshift_permute::{
    PermutePasses, Screen, SortInput, SortVariant, is_permutation_of, mask_offset, pack_mask_moves,
    retarget_seeds_cpu, sort_seeds_cpu,
};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// Push constants of the stand-in renderer (its GLSL `Push` block).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Push {
    width: u32,
    height: u32,
    stride: u32,
    frame: u32,
}

/// Sorting block edge: the paper's 4x4.
const BLOCK: u32 = 4;

/// Renders `frames` frames at `width` x `height`; returns the validation messages seen, the
/// device's destruction included.
fn run(width: u32, height: u32, frames: u64, validation: bool) -> Result<usize> {
    let instance = Instance::new(&InstanceDesc::from_env(validation))?;
    let dev = Device::new(&instance, &Default::default())?;
    frame_loop(&dev, width, height, frames)?;
    drop(dev);
    Ok(instance.validation_log().count())
}

/// The engine's frame loop: stand-in renderer, then the sorting pass, one submission a frame.
fn frame_loop(dev: &Device, width: u32, height: u32, frames: u64) -> Result<()> {
    // The textures: a 64x64 blue-noise mask and the table that carries mask frame t onto t+1.
    let assets = MethodAssets::load(&default_assets_dir())?;
    let screen = Screen::new(width, height, assets.n)?;
    let packed = pack_mask_moves(&assets.mask, &assets.table)?;
    let mask = Buffer::upload(dev, "engine.mask_moves", &packed)?;

    // Seeds: any distinct values, one per pixel of the padded screen, in two buffers that
    // swap every frame (the sort writes the next frame's seeds into the other one).
    let initial: Vec<u32> = (0..screen.seed_count() as u32)
        .map(|i| i.wrapping_mul(0x9e37_79b1))
        .collect();
    let seeds = [
        Buffer::upload(dev, "engine.seeds.a", &initial)?,
        Buffer::upload(dev, "engine.seeds.b", &initial)?,
    ];
    let pixels = u64::from(width) * u64::from(height);
    let estimate = Buffer::new(dev, "engine.estimate", pixels * 16, MemoryLocation::GpuOnly)?;
    // Host-readable copies for the check, filled by each frame's own submission.
    let host = MemoryLocation::GpuToCpu;
    let estimate_back = Buffer::new(dev, "engine.estimate.readback", estimate.size, host)?;
    let seeds_back = Buffer::new(dev, "engine.seeds.readback", seeds[0].size, host)?;

    let bindings = [
        Binding::storage(0, "seeds"),
        Binding::storage(1, "estimate"),
    ];
    let renderer = blueshift_shaders::pipeline(
        dev,
        "example/estimate_from_seeds",
        &bindings,
        size_of::<Push>(),
    )?;
    let mut passes = PermutePasses::new(dev)?;
    let mut rec = Recorder::new(dev, "engine.frame")?;
    let mut cpu_seeds = initial.clone();

    for frame in 0..frames {
        let (cur, next) = (frame as usize % 2, 1 - frame as usize % 2);
        // Frame t sorts against the mask shifted by exactly t times the table's shift.
        let sp = screen.sort_params(BLOCK, mask_offset(frame, assets.shift, assets.n))?;
        let push = Push {
            width,
            height,
            stride: screen.stride(),
            frame: frame as u32,
        };
        rec.begin()?;
        rec.begin_pass("estimate_from_seeds")?;
        rec.dispatch(
            &renderer,
            &[
                ("seeds", (&seeds[cur]).into()),
                ("estimate", (&estimate).into()),
            ],
            bytemuck::bytes_of(&push),
            [(pixels as u32).div_ceil(64), 1, 1],
        )?;
        rec.begin_pass("sort_seeds")?;
        let input = SortInput {
            retarget: Some(&seeds[next]),
            ..SortInput::new(&estimate, &mask)
        };
        let variant = SortVariant {
            retarget: true,
            large: SortVariant::large_for(BLOCK),
            ..SortVariant::PAPER
        };
        passes.sort_seeds(&mut rec, &sp, variant, &input, &seeds[cur])?;
        rec.copy_buffer(&estimate, &estimate_back, None)?;
        rec.copy_buffer(&seeds[next], &seeds_back, None)?;
        let times = rec.submit_and_wait()?;

        // The CPU twins on the same keys must give the same seeds, bit for bit.
        let keys: Vec<f32> = estimate_back
            .read::<[f32; 4]>()?
            .iter()
            .map(|e| e[3])
            .collect();
        let none = (vec![0; keys.len()], vec![0.0; keys.len()]);
        sort_seeds_cpu(&sp, &keys, &assets.mask, &none.0, &none.1, &mut cpu_seeds);
        cpu_seeds = retarget_seeds_cpu(&sp, &assets.table, &cpu_seeds);
        let gpu_seeds = seeds_back.read::<u32>()?;
        if gpu_seeds[..cpu_seeds.len()] != cpu_seeds[..] {
            return Err(format!("frame {frame}: GPU seeds differ from the CPU twins").into());
        }
        if !is_permutation_of(&cpu_seeds, &initial) {
            return Err(format!("frame {frame}: the seeds are no longer a permutation").into());
        }
        let ms = |name: &str| times.iter().find(|t| t.name == name).map_or(0.0, |t| t.ms);
        println!(
            "frame {frame}: renderer {:.2} ms, sort_seeds {:.2} ms, GPU == CPU",
            ms("estimate_from_seeds"),
            ms("sort_seeds")
        );
    }
    Ok(())
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: u32| -> Result<u32> {
        args.get(i).map_or(Ok(default), |s| {
            s.parse()
                .map_err(|_| format!("argument {} ('{s}') is not a number", i + 1).into())
        })
    };
    let (width, height, frames) = (arg(0, 160)?, arg(1, 96)?, arg(2, 8)?);
    let messages = run(width, height, u64::from(frames), false)?;
    println!("{frames} frames at {width}x{height}: seeds stay a permutation ({messages} messages)");
    Ok(())
}

#[cfg(test)]
mod tests {
    /// The example as the tests run it: validation on, a screen that is no multiple of the
    /// mask tile, and no validation message.
    #[test]
    fn engine_example_runs_clean() {
        let messages = super::run(100, 70, 6, true).expect("example runs");
        assert_eq!(messages, 0, "validation messages");
    }
}
