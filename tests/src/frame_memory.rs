//! Where a frame's memory lives and how its passes are ordered: every buffer a frame works on
//! is device-local (host-visible memory only for staging uploads and readbacks), and the
//! recorder puts barriers only between commands that depend on each other.
use crate::Gpu;
use blueshift_device::{Binding, Buffer, MemoryLocation};
use blueshift_layout::params::ImageParams;
use blueshift_render::{Method, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::Scene;

/// Host-visible memory has three legitimate uses, each named for it.
fn host_use_allowed(name: &str) -> bool {
    name.ends_with(".staging") || name.contains(".readback") || name.ends_with(".crash_marker")
}

/// Renders a few frames of every preset (a moving camera, so reprojecting methods reproject,
/// and with output readback on) and lists every live allocation: none that is not a staging
/// buffer or a readback may be host-visible.
#[test]
fn the_working_set_is_device_local() {
    let gpu = Gpu::new();
    let scene = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = blueshift_render::MethodAssets::load(&default_assets_dir()).unwrap();
    for (name, method) in Method::named() {
        if method == Method::Fast && assets.fast.is_empty() {
            continue;
        }
        let cfg = RenderConfig {
            method,
            bounces: 1,
            ..RenderConfig::new(40, 24)
        };
        let mut r = Renderer::new(gpu.dev(), &scene, &assets, cfg).unwrap();
        r.set_output_readback(true).unwrap();
        let base = r.camera();
        for f in 0..3 {
            let mut camera = base;
            camera.position.x += 0.01 * f as f32;
            r.set_camera(camera);
            r.submit_frame().unwrap();
        }
        let live = gpu.dev().allocations();
        let host: Vec<String> = live
            .iter()
            .filter(|a| a.location != MemoryLocation::GpuOnly && !host_use_allowed(&a.name))
            .map(|a| format!("{} ({} bytes, {:?})", a.name, a.bytes, a.location))
            .collect();
        assert!(
            host.is_empty(),
            "{name}: host-visible working buffers {host:?}"
        );
        for must in [
            "frame.estimate",
            "frame.accum",
            "frame.ldr",
            "frame.seeds.a",
        ] {
            assert!(live.iter().any(|a| a.name == must), "{name}: no {must}");
        }
        r.finish_frames().unwrap();
    }
}

/// Two accumulations that share only a read-only input record no barrier between them; the
/// tonemap that reads what the first wrote gets one (besides the one that starts every
/// command buffer), and every result is what the passes compute.
#[test]
fn barriers_only_between_dependent_dispatches() {
    let mut gpu = Gpu::new();
    let (w, h) = (8u32, 4u32);
    let n = (w * h) as usize;
    let estimate: Vec<[f32; 4]> = (0..n).map(|i| [i as f32 * 0.01, 0.5, 0.25, 1.0]).collect();
    let est = Buffer::from_slice(gpu.dev(), "test.estimate", &estimate).unwrap();
    let [a, b] = ["test.accum.a", "test.accum.b"].map(|s| gpu.output::<[f32; 4]>(s, n));
    let ldr = gpu.output::<u32>("test.ldr", n);
    let push = size_of::<ImageParams>() as u32;
    let accumulate = gpu.pipeline(
        "image/accumulate",
        &[
            Binding::storage(0, "estimate"),
            Binding::storage(1, "accum"),
        ],
        push,
    );
    let tonemap = gpu.pipeline(
        "image/tonemap",
        &[Binding::storage(0, "source"), Binding::storage(1, "ldr")],
        push,
    );
    let p = ImageParams {
        width: w,
        height: h,
        count: 0,
        exposure: 1.0,
    };
    let groups = [(w * h).div_ceil(64), 1, 1];
    let rec = gpu.rec.as_mut().unwrap();
    rec.begin().unwrap();
    let first = rec.barrier_count();
    for accum in [&a, &b] {
        let res = [("estimate", (&est).into()), ("accum", accum.into())];
        rec.dispatch(&accumulate, &res, bytemuck::bytes_of(&p), groups)
            .unwrap();
    }
    assert_eq!(rec.barrier_count(), first, "independent accumulations");
    let res = [("source", (&a).into()), ("ldr", (&ldr).into())];
    rec.dispatch(&tonemap, &res, bytemuck::bytes_of(&p), groups)
        .unwrap();
    assert_eq!(rec.barrier_count(), first + 1, "tonemap after accumulate");
    rec.submit_and_wait().unwrap();
    let bits = |v: Vec<[f32; 4]>| v.iter().map(|p| p.map(f32::to_bits)).collect::<Vec<_>>();
    let want = bits(estimate.clone());
    assert_eq!(bits(a.read::<[f32; 4]>().unwrap()[..n].to_vec()), want);
    assert_eq!(bits(b.read::<[f32; 4]>().unwrap()[..n].to_vec()), want);
    let rgba = ldr.read::<u32>().unwrap();
    assert!(
        rgba[..n].iter().all(|&px| px >> 24 == 255),
        "tonemap wrote every pixel"
    );
}
