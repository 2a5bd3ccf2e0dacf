//! Anchored masks: a mask that moves with the image instead of staying on the screen.
//!
//! A screen-fixed mask (blue-noise or spatio-temporal) gives each surface point a new mask
//! value whenever the image moves, so a temporal filter that follows the surface averages
//! unrelated values. Here every pixel carries an *anchor*, a fixed-point screen position
//! packed in its seed (x in the low 16 bits, y in the high, [`ANCHOR_FRAC_BITS`] fraction
//! bits each, wrapping at 256 px), and the trace reads the mask there
//! (`TRACE_FLAG_MASK_ANCHORED`). Each frame `follow_anchors` moves the anchors with the
//! surfaces: a pixel whose surface the previous frame saw at continuous position c takes the
//! anchor of pixel s = floor(c) plus c's offset from s's centre. Under a rigid motion the
//! anchors of a surface stay exactly where they were on it; pixels with no such surface
//! (sky, disocclusions) keep their own anchor. CPU twin of shaders/permute/follow_anchors.comp.
use crate::reproject::seen_before;
use blueshift_layout::motion::{GBufferTexel, MotionParams};
use blueshift_layout::params::ANCHOR_FRAC_BITS;
use glam::Vec2;

/// Anchors wrap at this many pixels: a mask tile must divide it.
pub const ANCHOR_WRAP: u32 = 1 << (16 - ANCHOR_FRAC_BITS);

/// The anchor of the centre of padded pixel (x, y): the frame-0 seed of an anchored method.
pub fn anchor_at(x: u32, y: u32) -> u32 {
    let one = 1u32 << ANCHOR_FRAC_BITS;
    let c = |v: u32| (v.wrapping_mul(one) + one / 2) & 0xffff;
    c(x) | (c(y) << 16)
}

/// Frame-0 anchors of a padded screen `stride` wide: every pixel's own centre.
pub fn initial_anchors(count: usize, stride: u32) -> Vec<u32> {
    (0..count as u32)
        .map(|i| anchor_at(i % stride, i / stride))
        .collect()
}

/// The whole pixel an anchor reads the mask at.
pub fn anchor_pixel(anchor: u32) -> (u32, u32) {
    (
        (anchor & 0xffff) >> ANCHOR_FRAC_BITS,
        (anchor >> 16) >> ANCHOR_FRAC_BITS,
    )
}

/// Fixed-point offset of `c` from the centre of pixel `s` (ties to even, as the shader).
fn step_of(c: f32, s: f32) -> u32 {
    let d = (c - (s + 0.5)) * (1u32 << ANCHOR_FRAC_BITS) as f32;
    d.round_ties_even() as i32 as u32
}

/// `follow_anchors`: this frame's anchors (padded, stride `p.padded_width`) from the previous
/// frame's (`anchors`), G-buffers and camera (`p`).
pub fn follow_anchors_cpu(
    p: &MotionParams,
    prev: &[GBufferTexel],
    cur: &[GBufferTexel],
    anchors: &[u32],
) -> Vec<u32> {
    let pw = p.padded_width;
    let mut out = anchors.to_vec();
    for y in 0..p.height {
        for x in 0..p.width {
            let g = &cur[(y * p.width + x) as usize];
            if let Some((c, (sx, sy))) = seen_before(p, prev, g) {
                let f = Vec2::new(sx as f32, sy as f32);
                out[(y * pw + x) as usize] = moved(anchors[(sy * pw + sx) as usize], c, f);
            }
        }
    }
    out
}

/// Anchor `from` (of the pixel at `f`) moved to continuous position `c`.
fn moved(from: u32, c: Vec2, f: Vec2) -> u32 {
    let x = (from & 0xffff).wrapping_add(step_of(c.x, f.x)) & 0xffff;
    let y = (from >> 16).wrapping_add(step_of(c.y, f.y)) & 0xffff;
    x | (y << 16)
}

/// The `follow_anchors` pass on the GPU.
pub struct FollowAnchors {
    pass: blueshift_device::ComputePipeline,
}

impl std::fmt::Debug for FollowAnchors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FollowAnchors").finish_non_exhaustive()
    }
}

impl FollowAnchors {
    pub fn new(dev: &blueshift_device::Device) -> crate::Result<Self> {
        use blueshift_device::Binding;
        let bindings = ["prev", "cur", "anchors_in", "anchors_out"]
            .iter()
            .enumerate()
            .map(|(i, n)| Binding::storage(i as u32, n))
            .collect::<Vec<_>>();
        let push = size_of::<MotionParams>();
        Ok(Self {
            pass: blueshift_shaders::pipeline(dev, "permute/follow_anchors", &bindings, push)?,
        })
    }

    /// Records `follow_anchors`: `anchors_out` from `anchors_in` and the two G-buffers.
    pub fn follow_anchors(
        &self,
        rec: &mut blueshift_device::Recorder,
        p: &MotionParams,
        prev: &blueshift_device::Buffer,
        cur: &blueshift_device::Buffer,
        anchors_in: &blueshift_device::Buffer,
        anchors_out: &blueshift_device::Buffer,
    ) -> crate::Result<()> {
        let groups = [p.padded_width.div_ceil(8), p.padded_height.div_ceil(8), 1];
        rec.dispatch(
            &self.pass,
            &[
                ("prev", prev.into()),
                ("cur", cur.into()),
                ("anchors_in", anchors_in.into()),
                ("anchors_out", anchors_out.into()),
            ],
            bytemuck::bytes_of(p),
            groups,
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Anchors round-trip to their pixel and wrap at ANCHOR_WRAP.
    #[test]
    fn an_anchor_reads_its_own_pixel() {
        for (x, y) in [(0, 0), (5, 9), (255, 17), (256, 300), (1000, 2)] {
            assert_eq!(
                anchor_pixel(anchor_at(x, y)),
                (x % ANCHOR_WRAP, y % ANCHOR_WRAP)
            );
        }
    }

    /// Moving by a continuous offset and back returns the anchor; a move of a whole pixel
    /// moves the anchor's pixel by one.
    #[test]
    fn moves_are_exact_in_fixed_point() {
        let a = anchor_at(10, 20);
        let f = Vec2::new(3.0, 4.0);
        let c = Vec2::new(3.5 + 1.0, 4.5 - 2.0); // one pixel right, two up of s's centre
        let b = moved(a, c, f);
        assert_eq!(anchor_pixel(b), (11, 18));
        let back = moved(b, Vec2::new(3.5 - 1.0, 4.5 + 2.0), f);
        assert_eq!(back, a);
        // Sub-pixel: a quarter pixel is 64 fixed-point steps.
        let q = moved(a, Vec2::new(3.75, 4.5), f);
        assert_eq!((q & 0xffff) - (a & 0xffff), 1 << (ANCHOR_FRAC_BITS - 2));
    }
}
