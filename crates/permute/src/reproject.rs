//! Seed reprojection: seeds follow their surface from one frame to the next and the seed
//! buffer stays a permutation. CPU twins of shaders/permute/reproject_*.comp.
//!
//! 1. motion: each pixel q of the new frame finds the pixel p of the previous frame that showed
//!    its surface (hit point projected with the previous camera, G-buffers `similar`), or none.
//! 2. claim: each p goes to the lowest q that wants it.
//! 3. gather: winners take p's seed; every other padded pixel is a hole.
//! 4. fill + 5. scatter: holes and unclaimed pixels (whose seeds no longer map anywhere) are
//!    listed in scan order; the k-th hole gets the k-th unclaimed pixel's seed. Both lists have
//!    the same length (each claimed pixel has exactly one winner), so the result is a
//!    permutation. Disoccluded pixels thus get fresh seeds, deterministically.
use crate::similar::dot3;
use blueshift_layout::motion::{
    GBufferTexel, MotionParams, REPROJECT_MAX_MOTION, REPROJECT_NONE, REPROJECT_TIE_BIAS,
};
use glam::{Vec2, Vec3};

/// Where the previous camera of `p` saw the world point `position`: its continuous pixel
/// position (pixel centres at `x + 0.5`) and its depth along the previous view direction (not
/// positive: behind that camera, the position means nothing). The shader's operations, in its
/// order.
pub fn project_previous(p: &MotionParams, position: Vec3) -> (Vec2, f32) {
    let d = position - p.cam_origin;
    let z = dot3(d, p.cam_forward);
    let nx = dot3(d, p.cam_right) / (dot3(p.cam_right, p.cam_right) * z);
    let ny = -dot3(d, p.cam_up) / (dot3(p.cam_up, p.cam_up) * z);
    (
        (Vec2::new(nx, ny) + 1.0) * 0.5 * p.view_size - p.view_offset,
        z,
    )
}

/// Where the previous frame saw the surface of G-buffer texel `g`: the continuous position of
/// its hit point and the pixel there, if that pixel is on screen and showed a `similar`
/// surface (sky never has a source).
pub(crate) fn seen_before(
    p: &MotionParams,
    prev: &[GBufferTexel],
    g: &GBufferTexel,
) -> Option<(Vec2, (u32, u32))> {
    let (c, z) = project_previous(p, g.position);
    let f = (c + REPROJECT_TIE_BIAS).floor();
    let inside =
        z > 0.0 && f.x >= 0.0 && f.y >= 0.0 && f.x < p.width as f32 && f.y < p.height as f32;
    if !inside || g.material == 0 {
        return None;
    }
    let s = (f.x as u32, f.y as u32);
    crate::similar(g, &prev[(s.1 * p.width + s.0) as usize]).then_some((c, s))
}

/// Step 1 (`reproject_motion`): source pixel (padded index) per padded pixel, or NONE.
pub fn reproject_motion_cpu(
    p: &MotionParams,
    prev: &[GBufferTexel],
    cur: &[GBufferTexel],
) -> Vec<u32> {
    let (pw, ph) = (p.padded_width, p.padded_height);
    let mut src = vec![REPROJECT_NONE; (pw * ph) as usize];
    for y in 0..p.height {
        for x in 0..p.width {
            let g = &cur[(y * p.width + x) as usize];
            if let Some((_, (sx, sy))) = seen_before(p, prev, g) {
                src[(y * pw + x) as usize] = sy * pw + sx;
            }
        }
    }
    src
}

/// What steps 2-5 produce.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Reprojected {
    /// The new seed buffer (padded), a permutation of the input.
    pub seeds: Vec<u32>,
    /// Sum of the winners' motion (x, y; each clamped to +-REPROJECT_MAX_MOTION) and their count.
    pub motion: [i32; 3],
}

impl Reprojected {
    /// The winners' mean motion rounded to whole pixels ((0, 0) if nothing reprojected).
    pub fn mean_motion(&self) -> (i32, i32) {
        mean_motion(self.motion)
    }
}

/// Mean of motion sums `[sum x, sum y, count]`, rounded half away from zero.
pub fn mean_motion(m: [i32; 3]) -> (i32, i32) {
    if m[2] <= 0 {
        return (0, 0);
    }
    let r = |s: i32| (s as f64 / m[2] as f64).round() as i32;
    (r(m[0]), r(m[1]))
}

/// Steps 2-5 (`reproject_claim`, `_gather`, `_fill`, `_scatter`) on any source field `src`
/// (padded indices or NONE; several pixels may want the same source).
pub fn reproject_seeds_cpu(p: &MotionParams, src: &[u32], seeds_in: &[u32]) -> Reprojected {
    let pw = p.padded_width as usize;
    let n = pw * p.padded_height as usize;
    let mut claim = vec![REPROJECT_NONE; n];
    for (q, &s) in src.iter().enumerate().take(n) {
        if s != REPROJECT_NONE {
            claim[s as usize] = claim[s as usize].min(q as u32);
        }
    }
    let mut out = vec![0u32; n];
    let mut motion = [0i32; 3];
    let (mut holes, mut leftovers) = (Vec::new(), Vec::new());
    for q in 0..n {
        let s = src[q];
        if s != REPROJECT_NONE && claim[s as usize] == q as u32 {
            out[q] = seeds_in[s as usize];
            let s = s as usize;
            let lim = REPROJECT_MAX_MOTION;
            motion[0] += ((q % pw) as i32 - (s % pw) as i32).clamp(-lim, lim);
            motion[1] += ((q / pw) as i32 - (s / pw) as i32).clamp(-lim, lim);
            motion[2] += 1;
        } else {
            holes.push(q);
        }
        if claim[q] == REPROJECT_NONE {
            leftovers.push(q);
        }
    }
    for (h, l) in holes.into_iter().zip(leftovers) {
        out[h] = seeds_in[l];
    }
    Reprojected { seeds: out, motion }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::is_permutation_of;

    fn params(w: u32, h: u32, pw: u32, ph: u32) -> MotionParams {
        MotionParams {
            cam_origin: glam::Vec3::ZERO,
            cam_forward: glam::Vec3::NEG_Z,
            cam_right: glam::Vec3::X,
            cam_up: glam::Vec3::Y,
            view_offset: Vec2::ZERO,
            view_size: Vec2::new(w as f32, h as f32),
            width: w,
            height: h,
            padded_width: pw,
            padded_height: ph,
        }
    }

    #[test]
    fn a_shift_moves_every_seed_and_refills_the_entering_edge() {
        // Content moves 3 px to the left: q takes q + 3; the 3 rightmost visible columns and
        // the padding are holes, refilled from the 3 leftmost columns and the padding.
        let p = params(10, 4, 16, 4);
        let src: Vec<u32> = (0..16 * 4)
            .map(|q| {
                let (x, y) = (q % 16, q / 16);
                if x + 3 < 10 {
                    y * 16 + x + 3
                } else {
                    REPROJECT_NONE
                }
            })
            .collect();
        let init: Vec<u32> = (100..100 + 64).collect();
        let r = reproject_seeds_cpu(&p, &src, &init);
        assert!(is_permutation_of(&r.seeds, &init));
        for y in 0..4 {
            for x in 0..7 {
                assert_eq!(r.seeds[y * 16 + x], init[y * 16 + x + 3]);
            }
        }
        assert_eq!(r.mean_motion(), (-3, 0));
    }

    #[test]
    fn collisions_keep_the_lowest_claimant() {
        let p = params(4, 1, 4, 1);
        let src = vec![2, 2, 2, REPROJECT_NONE];
        let r = reproject_seeds_cpu(&p, &src, &[10, 11, 12, 13]);
        // q0 wins 12; holes q1 q2 q3 get the unclaimed 10 11 13 in order.
        assert_eq!(r.seeds, vec![12, 10, 11, 13]);
        assert_eq!(r.motion, [-2, 0, 1]);
    }

    /// A wall seen head-on through a camera whose sensor moved by half a pixel: every pixel
    /// centre projects onto a pixel border of the previous frame, give or take float noise.
    /// All pixels must still take the same neighbour, or seeds collide and fresh seeds appear.
    #[test]
    fn a_half_pixel_shift_moves_all_pixels_alike() {
        let (w, h) = (37u32, 5u32);
        let right = glam::Vec3::X * 0.731;
        let up = glam::Vec3::Y * 0.731 * h as f32 / w as f32;
        let wall = |x: u32, y: u32| {
            let ndc = Vec2::new(
                (x as f32 + 0.5) / w as f32 * 2.0 - 1.0,
                1.0 - (y as f32 + 0.5) / h as f32 * 2.0,
            );
            let dir = (glam::Vec3::NEG_Z + ndc.x * right + ndc.y * up).normalize();
            let depth = 2.3 / -dir.z;
            GBufferTexel {
                position: dir * depth,
                material: 1,
                normal: glam::Vec3::Z,
                depth,
            }
        };
        let g: Vec<GBufferTexel> = (0..w * h).map(|q| wall(q % w, q / w)).collect();
        let p = MotionParams {
            cam_right: right,
            cam_up: up,
            view_offset: Vec2::new(0.5, 0.0),
            ..params(w, h, w, h)
        };
        let src = reproject_motion_cpu(&p, &g, &g);
        let mut shifts = std::collections::BTreeSet::new();
        for q in 0..w * h {
            let s = src[q as usize];
            if s != REPROJECT_NONE {
                assert_eq!(s / w, q / w, "pixel {q} left its row");
                shifts.insert(s as i64 - q as i64);
            }
        }
        assert_eq!(
            shifts.len(),
            1,
            "pixels took different neighbours: {shifts:?}"
        );
        let hits = src.iter().filter(|&&s| s != REPROJECT_NONE).count();
        assert!(
            hits >= ((w - 1) * h) as usize,
            "only {hits} pixels found a source"
        );
    }

    #[test]
    fn mean_motion_rounds_and_handles_no_winners() {
        assert_eq!(mean_motion([0, 0, 0]), (0, 0));
        assert_eq!(mean_motion([-15, 5, 10]), (-2, 1));
    }
}
