//! The `gbuffer` pass (shaders/trace/gbuffer.comp) and its CPU twin: the primary hit through
//! every pixel centre, which edge-aware grouping and seed reprojection compare between pixels
//! and frames.
use crate::buffers::SceneBuffers;
use crate::images::SceneImages;
use crate::pass::scene_resources;
use crate::{Result, TRACE_BINDINGS};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, Recorder};
use blueshift_layout::motion::GBufferTexel;
use blueshift_layout::params::TraceParams;
use blueshift_scene::{Ray, SceneGpu, closest_hit};
use glam::{Vec2, Vec3};

/// The G-buffer pipeline (the path tracer's scene bindings, then the output).
pub struct GBufferPass {
    pipeline: ComputePipeline,
}

impl std::fmt::Debug for GBufferPass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GBufferPass").finish_non_exhaustive()
    }
}

impl GBufferPass {
    pub fn new(dev: &Device) -> Result<Self> {
        let mut bindings: Vec<Binding> = TRACE_BINDINGS[..8].to_vec();
        bindings.push(Binding::storage(8, "gbuffer"));
        let push = size_of::<TraceParams>();
        Ok(Self {
            pipeline: blueshift_shaders::pipeline(dev, "trace/gbuffer", &bindings, push)?,
        })
    }

    /// Records the pass: one `GBufferTexel` per visible pixel into `out`, for the camera and
    /// view window of `p` (its sampler fields are ignored).
    pub fn gbuffer(
        &self,
        rec: &mut Recorder,
        p: &TraceParams,
        s: &SceneBuffers,
        i: &SceneImages,
        out: &Buffer,
    ) -> Result<()> {
        rec.dispatch(
            &self.pipeline,
            &[&scene_resources(s, i)[..], &[("gbuffer", out.into())]].concat(),
            bytemuck::bytes_of(p),
            [p.width.div_ceil(8), p.height.div_ceil(8), 1],
        )?;
        Ok(())
    }
}

/// CPU twin of the pass, with the CPU BVH traversal (equal to the GPU's: tests/src/bvh.rs).
pub fn gbuffer_cpu(scene: &SceneGpu, p: &TraceParams) -> Vec<GBufferTexel> {
    let mut out = Vec::with_capacity((p.width * p.height) as usize);
    for y in 0..p.height {
        for x in 0..p.width {
            let px = Vec2::new(x as f32, y as f32);
            let ndc = (px + p.view_offset + Vec2::splat(0.5)) / p.view_size * 2.0 - 1.0;
            let dir = (p.cam_forward + ndc.x * p.cam_right - ndc.y * p.cam_up).normalize();
            let ray = Ray::new(p.cam_origin, dir, 0.0, 1e30);
            let texel = match closest_hit(&scene.nodes, &scene.triangles, &ray) {
                Some(hit) => {
                    let tri = &scene.triangles[hit.triangle as usize];
                    let mut ng = tri.e1.cross(tri.e2).normalize();
                    if ng.dot(dir) > 0.0 {
                        ng = -ng;
                    }
                    GBufferTexel {
                        position: p.cam_origin + dir * hit.t,
                        material: scene.shading[hit.triangle as usize].material + 1,
                        normal: ng,
                        depth: hit.t,
                    }
                }
                None => GBufferTexel {
                    position: Vec3::ZERO,
                    material: 0,
                    normal: Vec3::ZERO,
                    depth: 0.0,
                },
            };
            out.push(texel);
        }
    }
    out
}
