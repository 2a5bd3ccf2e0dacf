//! The camera path's side of the TAA: per frame, the G-buffer through the pixel centres and the
//! reprojection from the previous frame. It comes from the CPU twin of the G-buffer pass, from
//! the path alone: the renderer's own G-buffer exists only for some methods and is the input
//! of the methods being measured, which must not shape the measuring filter.
use blueshift_layout::motion::GBufferTexel;
use blueshift_layout::params::TraceParams;
use blueshift_permute::Screen;
use blueshift_render::taa::Reprojection;
use blueshift_render::{CameraPath, gbuffer_cpu, motion_params};
use blueshift_scene::{Camera, SceneGpu};

/// Walks a camera path frame by frame (frames 0, 1, 2, ... in order).
pub struct Track<'a> {
    scene: &'a SceneGpu,
    path: &'a CameraPath,
    base: Camera,
    size: (u32, u32),
    view: (u32, u32),
    base_offset: (f32, f32),
    prev: Option<(TraceParams, Vec<GBufferTexel>)>,
}

impl<'a> Track<'a> {
    /// A `frames`-frame run of `path` from `base` at `width x height`, laid out on its sensor
    /// as eval renders it (`CameraPath::view_window`).
    pub fn new(
        scene: &'a SceneGpu,
        path: &'a CameraPath,
        base: Camera,
        frames: u32,
        size: (u32, u32),
    ) -> Self {
        let (view, base_offset) = path.view_window(frames, size.0, size.1);
        Self {
            scene,
            path,
            base,
            size,
            view,
            base_offset,
            prev: None,
        }
    }

    /// The camera part of frame `t`'s trace parameters (what the G-buffer pass reads): the
    /// renderer's basis for the path's camera and sensor window.
    pub fn params(&self, t: u32) -> TraceParams {
        let (vw, vh) = self.view;
        let b = self.path.camera(&self.base, t).basis(vw as f32 / vh as f32);
        let o = self.path.view_offset(t);
        TraceParams {
            cam_origin: b.position,
            cam_forward: b.forward,
            cam_right: b.right,
            cam_up: b.up,
            width: self.size.0,
            height: self.size.1,
            view_offset: glam::Vec2::new(self.base_offset.0 + o.0, self.base_offset.1 + o.1),
            view_size: glam::Vec2::new(vw as f32, vh as f32),
            ..bytemuck::Zeroable::zeroed()
        }
    }

    /// The reprojection from frame `t - 1` into frame `t` (`None` for the first frame asked
    /// for). A frame seen by the same camera as its predecessor keeps every pixel's history
    /// exactly, as the EMA does: projecting its hit points back would land within float
    /// rounding of the pixel centres, which bilinear weights would turn into a slight blur.
    pub fn next(&mut self, t: u32) -> Option<Reprojection> {
        let p = self.params(t);
        let same = |q: &TraceParams| bytemuck::bytes_of(q) == bytemuck::bytes_of(&p);
        let pixels = (self.size.0 * self.size.1) as usize;
        match self.prev.take() {
            Some((q, g)) if same(&q) => {
                self.prev = Some((q, g));
                Some(Reprojection::still(pixels))
            }
            prev => {
                let g = gbuffer_cpu(self.scene, &p);
                let r = prev.map(|(q, pg)| {
                    // The padding of the screen is irrelevant here (tile 1: none).
                    let screen = Screen::new(self.size.0, self.size.1, 1).ok();
                    let cam = screen.map(|s| motion_params(&q, &s));
                    cam.map_or_else(
                        || Reprojection::from_sources(&g, &pg, &vec![None; pixels], self.size.0),
                        |c| Reprojection::new(&g, &pg, &c, self.size.0),
                    )
                });
                self.prev = Some((p, g));
                r
            }
        }
    }
}

/// The reprojection into each of `frames` frames of `path` (`None` for frame 0), from the scene's
/// default camera: what every method and sequence of one path share.
pub fn motions(
    scene: &SceneGpu,
    path: &CameraPath,
    base: &blueshift_scene::Scene,
    frames: u32,
    size: (u32, u32),
) -> Vec<Option<Reprojection>> {
    let mut track = Track::new(scene, path, base.camera_or_default(), frames, size);
    (0..frames).map(|t| track.next(t)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use blueshift_render::default_assets_dir;
    use blueshift_scene::Scene;

    fn cornell() -> (SceneGpu, Camera) {
        let s = Scene::load(default_assets_dir().join("scenes/cornell-box.gltf")).unwrap();
        (SceneGpu::build(&s), s.camera_or_default())
    }

    /// A still path keeps every pixel; a sensor pan of whole pixels moves the hit points by
    /// exactly that much and keeps all but the entering columns.
    #[test]
    fn still_and_panned_paths_move_their_hit_points_as_the_sensor_moves() {
        let (scene, base) = cornell();
        let size = (48, 40);
        let still = CameraPath::Static;
        let mut t = Track::new(&scene, &still, base, 4, size);
        assert!(t.next(0).is_none());
        let r = t.next(1).unwrap();
        assert_eq!(r, Reprojection::still(48 * 40));
        let pan = CameraPath::Pan { px_per_frame: 2.0 };
        let mut t = Track::new(&scene, &pan, base, 4, size);
        assert!(t.next(0).is_none());
        let r = t.next(1).unwrap();
        assert!((r.motion_px - 2.0).abs() < 1e-3, "{}", r.motion_px);
        let entering = 2.0 / 48.0;
        assert!(
            r.kept_share() <= 1.0 - entering + 1e-9 && r.kept_share() > 0.9 - entering,
            "{}",
            r.kept_share()
        );
    }
}
