//! `blueshift info`: what the device offers a path tracer, and a verified compute dispatch.
use crate::GpuOpts;
use anyhow::{Result, bail};
use blueshift_device::{
    Binding, Buffer, ComputePipeline, Device, DeviceDesc, Instance, InstanceDesc, MemoryLocation,
    Recorder, list_physical_devices,
};
use blueshift_sampling::rng::{hash3, pcg_hash, pixel_seed, white};

#[derive(clap::Args, Debug)]
pub struct InfoArgs {
    /// Skip the verification dispatch.
    #[arg(long)]
    no_smoke: bool,
}

pub fn run(gpu: &GpuOpts, args: &InfoArgs) -> Result<()> {
    let instance = Instance::new(&InstanceDesc::from_env(gpu.validation))?;
    for (i, name) in list_physical_devices(&instance)?.iter().enumerate() {
        println!("vulkan device {i}: {name}");
    }
    let dev = Device::new(
        &instance,
        &DeviceDesc {
            device_index: gpu.device_index,
            surface: None,
        },
    )?;
    let i = dev.info();
    println!("selected:            {} ({})", i.name, i.device_type);
    println!(
        "api / driver:        {} / {} {}",
        i.api_version, i.driver_name, i.driver_info
    );
    println!("subgroup size:       {}", i.subgroup_size);
    println!(
        "maxStorageBufferRange: {} MiB",
        i.max_storage_buffer_range >> 20
    );
    println!(
        "maxMemoryAllocationSize: {} MiB",
        i.max_memory_allocation_size >> 20
    );
    println!("memory budget:       {} MiB", i.memory_budget >> 20);
    println!(
        "compute: {} invocations/group, {:?} groups, {} KiB shared",
        i.max_compute_work_group_invocations,
        i.max_compute_work_group_count,
        i.max_compute_shared_memory_size >> 10
    );
    println!("maxImageDimension2D: {}", i.max_image_dimension_2d);
    println!("maxPushConstantsSize: {} B", i.max_push_constants_size);
    println!(
        "timestamps:          {} valid bits, period {} ns",
        i.timestamp_valid_bits, i.timestamp_period_ns
    );
    println!(
        "shaderInt64 {}  shaderFloat64 {}  scalarBlockLayout {}  push_descriptor {}",
        i.shader_int64, i.shader_float64, i.scalar_block_layout, i.push_descriptor
    );
    println!(
        "validation:          {}",
        if instance.validation_enabled() {
            "on"
        } else {
            "off"
        }
    );
    if !args.no_smoke {
        smoke(&dev)?;
    }
    let msgs = dev.validation_messages();
    if !msgs.is_empty() {
        bail!("{} validation message(s) (see above)", msgs.len());
    }
    Ok(())
}

/// Runs the rng shader over 2^20 inputs and compares with the CPU twin.
fn smoke(dev: &Device) -> Result<()> {
    let n: u32 = 1 << 20;
    let spirv = blueshift_shaders::require("test/rng").map_err(anyhow::Error::msg)?;
    let pipe = ComputePipeline::new(
        dev,
        "test/rng",
        &spirv,
        &[Binding::storage(0, "results")],
        8,
    )?;
    let out = Buffer::new(
        dev,
        "smoke.results",
        n as u64 * 16,
        MemoryLocation::GpuToCpu,
    )?;
    let mut rec = Recorder::new(dev, "smoke")?;
    rec.begin()?;
    rec.begin_pass("smoke.rng")?;
    rec.dispatch(
        &pipe,
        &[("results", (&out).into())],
        bytemuck::cast_slice(&[0u32, n]),
        [n.div_ceil(64), 1, 1],
    )?;
    let times = rec.submit_and_wait()?;
    let got = out.read::<[u32; 4]>()?;
    let bad = (0..n)
        .filter(|&v| {
            got[v as usize]
                != [
                    pcg_hash(v),
                    hash3(v, v.wrapping_mul(3), 7),
                    white(v, 5, v & 15).to_bits(),
                    pixel_seed(v, !v, 1),
                ]
        })
        .count();
    let ms = times.first().map_or(0.0, |t| t.ms);
    if bad > 0 {
        bail!("compute smoke test: {bad} of {n} results differ from the CPU twin");
    }
    println!("compute smoke test:  {n} hashes verified against the CPU twin ({ms:.2} ms GPU)");
    Ok(())
}
