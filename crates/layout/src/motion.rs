//! Structs of the G-buffer and of the passes that use it (edge-aware grouping and seed
//! reprojection), shared with GLSL (`generated/motion.glsl`).
use crate::gpu_struct;

gpu_struct! {
    /// One pixel of the G-buffer: the primary hit through the pixel centre.
    pub struct GBufferTexel {
        /// World-space hit point.
        pub position: glam::Vec3,
        /// Material index + 1 of the hit triangle; 0 = the ray left the scene.
        pub material: u32,
        /// Unit geometric normal, facing the camera.
        pub normal: glam::Vec3,
        /// Ray parameter of the hit (the distance: camera directions are unit length).
        pub depth: f32,
    }
}

gpu_struct! {
    /// Push constants of `permute/reproject_motion`: where each pixel's surface was in the
    /// previous frame, seen by the previous frame's camera.
    pub struct MotionParams {
        /// Previous camera: origin and basis as in `TraceParams` (direction through pixel p
        /// = forward + ndc.x * right - ndc.y * up, ndc = (p + 0.5 + view_offset) / view_size
        /// * 2 - 1).
        pub cam_origin: glam::Vec3,
        pub cam_forward: glam::Vec3,
        pub cam_right: glam::Vec3,
        pub cam_up: glam::Vec3,
        pub view_offset: glam::Vec2,
        pub view_size: glam::Vec2,
        /// Visible screen.
        pub width: u32,
        pub height: u32,
        /// Padded seed-buffer size.
        pub padded_width: u32,
        pub padded_height: u32,
    }
}

gpu_struct! {
    /// Push constants of `image/taa`, the accumulation along the motion (TAA): the previous
    /// frame's camera and the screen as the reprojection passes take them (`padded_*` unused).
    pub struct TaaParams {
        pub camera: MotionParams,
        /// 1 when the previous frame had this frame's camera: every pixel keeps its own
        /// history with weight 1 (the plain EMA), as the CPU twin's still camera does.
        pub still: u32,
    }
}

/// Weight of the newest frame in the TAA (the EMA's weight too).
pub const TAA_ALPHA: f32 = 0.1;
/// The TAA's bilinear positions are rounded to 1/TAA_SNAP px: the projection's float noise
/// (~1e-5 px) would otherwise give a tap off screen or on another surface a tiny weight, which
/// renormalisation could turn into the whole history; whole-pixel motions stay whole.
pub const TAA_SNAP: f32 = 256.0;

gpu_struct! {
    /// Push constants of `permute/history_key`: each pixel's history mean (its surface's mean
    /// sorting key over earlier frames, fetched through the reprojection's source map).
    pub struct HistoryParams {
        /// Visible screen.
        pub width: u32,
        pub height: u32,
        /// Padded width: the row stride of the reprojection's `src` and of the histories.
        pub padded_width: u32,
        /// 1 when `src` maps this frame's pixels to the previous frame's; 0 on the first frame
        /// of a sequence (every history restarts, every pixel ranks its raw key).
        pub has_history: u32,
        /// Histories of fewer frames are too noisy to rank against and are left out of the
        /// window below; a pixel whose window has none gets NaN (the sorting pass then uses
        /// its class's mean key in the block).
        pub min_frames: u32,
        /// The mean weighs the newest key by 1 / min(frames, max_frames).
        pub max_frames: u32,
    }
}

/// `HistoryParams::min_frames` and `max_frames` of `sort-grid-history` (docs/algorithm.md,
/// "key=history": single-pixel histories of one or two frames made pans worse; with the 3x3
/// window a minimum of 4 frames beat 8 on pans, a maximum of 16 frames lost to 64 under
/// rotation, and a 5x5 window gained nothing over 3x3).
///
/// A pixel ranks against the mean of the histories in its 3x3 window that show its surface
/// (`similar` G-buffer texels): the window averages the history's own noise down in smooth
/// regions, and over a symmetric window a linear gradient averages to its centre value, so
/// only curvature biases it.
pub const HISTORY_MIN_FRAMES: u32 = 4;
pub const HISTORY_MAX_FRAMES: u32 = 64;
/// Rows of the strip one `history_key` invocation walks down (its window's rows stay in
/// registers, so each is fetched once per strip rather than once per pixel).
pub const HISTORY_STRIP: u32 = 16;
/// Columns of that strip per invocation (the shader's tap rows are unrolled for 4).
pub const HISTORY_COLUMNS: u32 = 4;

/// "No pixel" in the reprojection buffers.
pub const REPROJECT_NONE: u32 = 0xffff_ffff;
/// Added to a pixel's projected position before it is rounded down to its source pixel: a
/// motion of an odd number of half pixels puts pixel centres exactly on pixel borders, where
/// float noise would pick either side (collisions, fresh seeds); 1/256 px off the borders,
/// every pixel picks the same side.
pub const REPROJECT_TIE_BIAS: f32 = 0.003_906_25;
/// Largest per-pixel motion (pixels per axis) counted in the mean motion that moves the
/// mask with the image; larger moves are clamped (keeps the integer sums from overflowing).
pub const REPROJECT_MAX_MOTION: i32 = 255;
/// Surface similarity (G-buffer pixels a, b are one surface): same material, normals within
/// acos(0.9) ~ 26 degrees, and a's distance from b's tangent plane under this fraction of the
/// larger depth.
pub const SIMILAR_MIN_COS: f32 = 0.9;
pub const SIMILAR_PLANE_DISTANCE: f32 = 0.02;
