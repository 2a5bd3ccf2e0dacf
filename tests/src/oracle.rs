//! Oracle keys (`permute/oracle_key`, `sort-grid-oracle`): GPU == CPU twin, the key is exactly
//! the error the metrics measure, and the renderer refuses a frame without its reference.
use crate::{Gpu, Lcg};
use blueshift_analysis::luminance;
use blueshift_device::Buffer;
use blueshift_layout::motion::OracleParams;
use blueshift_permute::{OracleKeys, oracle_key_cpu};
use blueshift_render::{Method, MethodAssets, RenderConfig, Renderer, default_assets_dir};
use blueshift_scene::Scene;

#[test]
fn oracle_keys_match_cpu_and_the_metric_error() {
    let mut gpu = Gpu::new();
    let mut rng = Lcg(29);
    for (w, h) in [(37, 23), (64, 48)] {
        let n = (w * h) as usize;
        // Radiance-like values with zeros and a wide range, and keys the pass must replace.
        let est: Vec<[f32; 4]> = (0..n)
            .map(|i| {
                let s = if i % 7 == 0 {
                    0.0
                } else {
                    1.0 + 30.0 * rng.unit()
                };
                [s * rng.unit(), s * rng.unit(), s * rng.unit(), -5.0]
            })
            .collect();
        let reference: Vec<f32> = (0..n).map(|_| 4.0 * rng.unit()).collect();
        let mut keys = OracleKeys::new(gpu.dev(), w, h).unwrap();
        keys.set_reference(&reference).unwrap();
        let mut est_b = Buffer::new(
            gpu.dev(),
            "oracle.estimate",
            n as u64 * 16,
            blueshift_device::MemoryLocation::CpuToGpu,
        )
        .unwrap();
        est_b.write(0, &est).unwrap();
        let rec = gpu.rec.as_mut().unwrap();
        rec.begin().unwrap();
        rec.begin_pass("oracle_key").unwrap();
        let p = OracleParams {
            width: w,
            height: h,
        };
        keys.oracle_key(rec, &p, &est_b).unwrap();
        rec.submit_and_wait().unwrap();
        let got = est_b.read::<[f32; 4]>().unwrap();
        let mut want = est.clone();
        oracle_key_cpu(&mut want, &reference);
        for i in 0..n {
            // Bit for bit: the same float operations in the same order (`precise`).
            assert_eq!(
                got[i].map(f32::to_bits),
                want[i].map(f32::to_bits),
                "{w}x{h} #{i}"
            );
            // The key is the metric's per-pixel error e_t (evaluation.md), computed by the
            // analysis crate's luminance, so the sort ranks exactly what P1 measures.
            let e = luminance([est[i][0], est[i][1], est[i][2]]) - reference[i];
            assert_eq!(
                got[i][3].to_bits(),
                e.to_bits(),
                "{w}x{h} #{i} vs the metric"
            );
        }
    }
    let mut keys = OracleKeys::new(gpu.dev(), 4, 4).unwrap();
    let err = keys.set_reference(&[0.0; 15]).unwrap_err().to_string();
    assert!(err.contains("15 pixels"), "{err}");
}

/// Without this frame's reference the oracle method fails with an error naming it, and a
/// reference set for an earlier frame does not count.
#[test]
fn oracle_method_needs_each_frames_reference() {
    let gpu = Gpu::new();
    let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let cfg = RenderConfig {
        bounces: 1,
        method: Method::SortGridOracle,
        ..RenderConfig::new(24, 16)
    };
    let mut r = Renderer::new(
        gpu.dev(),
        &s,
        &MethodAssets::load(&default_assets_dir()).unwrap(),
        cfg,
    )
    .unwrap();
    let err = r.render_frame().unwrap_err().to_string();
    assert!(
        err.contains("sort-grid-oracle") && err.contains("reference"),
        "{err}"
    );
    r.set_reference_luminance(&[0.5; 24 * 16]).unwrap();
    r.render_frame().unwrap();
    let err = r.render_frame().unwrap_err().to_string();
    assert!(err.contains("frame 1"), "{err}");
    assert!(r.set_reference_luminance(&[0.5; 10]).is_err());
}
