//! A sample of every spelled-out method the passes can run, rendered still and then moving
//! under validation: each frame's recipe (the render crate checks them all on the CPU) runs on
//! the device with the buffers its shaders declare, the seeds stay a permutation and the
//! estimates finite.
use crate::Gpu;
use blueshift_render::{
    Method, MethodAssets, Permutation, RenderConfig, Renderer, Without, default_assets_dir,
};
use blueshift_scene::Scene;

/// One form in this many (and every preset's): a spread over the fields' combinations that
/// keeps the test at a few seconds. The ablations (`without=`) only switch host-side flags
/// of shader variants the other forms run, so the sample takes the default's four.
const EVERY: usize = 11;

#[test]
fn a_sample_of_every_form_renders_still_and_moving() {
    let gpu = Gpu::new();
    let scene = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
    let assets = MethodAssets::load(&default_assets_dir()).unwrap();
    // The default's ablations are the forms that differ from it in `without` alone.
    let cycle = Method::SORT_CYCLE.permutation().unwrap();
    let (ablations, forms): (Vec<Method>, Vec<Method>) =
        Method::all_permutations().into_iter().partition(|m| {
            m.permutation()
                .is_some_and(|p| p.without != Without::Nothing)
        });
    let ablations = ablations.into_iter().filter(|m| {
        m.permutation().is_some_and(|p| {
            Permutation {
                without: Without::Nothing,
                ..p
            } == cycle
        })
    });
    let presets: Vec<Method> = Method::PRESETS.iter().map(|(_, m)| *m).collect();
    let sample: Vec<Method> = forms
        .iter()
        .enumerate()
        .filter(|(i, m)| i % EVERY == 0 || presets.contains(m))
        .map(|(_, m)| *m)
        .chain(ablations)
        .collect();
    assert!(sample.len() > forms.len() / EVERY, "{} forms", sample.len());
    for method in sample {
        let cfg = RenderConfig {
            bounces: 2,
            method,
            ..RenderConfig::new(20, 14)
        };
        let mut r = Renderer::new(gpu.dev(), &scene, &assets, cfg).unwrap();
        let init = r.initial_seeds().to_vec();
        let mut cam = scene.camera_or_default();
        for frame in 0..5 {
            if frame >= 2 {
                cam.position.x += 0.03;
                r.set_camera(cam);
            }
            assert_eq!(r.moving(), frame >= 2, "{method}");
            r.render_frame().unwrap();
            let seeds = r.read_seeds().unwrap();
            assert!(
                blueshift_permute::is_permutation_of(&seeds, &init),
                "{method}, frame {frame}: seeds are no permutation"
            );
            let est = r.read_estimate().unwrap();
            assert!(
                est.iter().flatten().all(|v| v.is_finite()),
                "{method}, frame {frame}: a non-finite estimate"
            );
        }
    }
}
