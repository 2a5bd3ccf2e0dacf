//! CPU twin of sort-cycle's shading edges (`shaders/include/shade_edges.glsl`, run by the
//! sorting pass): pixels whose running mean jumps inside their surface class in the sorting
//! block. The sorting pass ranks them in classes of their own and marks them in the trace's
//! `primary_flags`, whose next frame takes their light sample from the rotating mask.
use crate::SortParams;
use blueshift_layout::params::{
    PRIMARY_SHADE_EDGE, SHADE_EDGE_CLASS, SHADE_EDGE_MAX_MEAN, SHADE_EDGE_MIN_FRAMES,
    SHADE_EDGE_PER_MILLE, SHADE_EDGE_SCALE,
};

/// The running mean in fixed point (the GPU's `shade_edge_fixed`); NaN and negatives give 0.
pub fn shade_edge_fixed(m: f32) -> u32 {
    if m > 0.0 {
        (m.min(SHADE_EDGE_MAX_MEAN) * SHADE_EDGE_SCALE) as u32
    } else {
        0
    }
}

/// The marks of every visible pixel under `p` (sort-cycle's fixed blocks): `means` the
/// running mean's `.w` and `classes` the sort's classes, per visible pixel. Inside each block,
/// the fixed-point mean blurred 3x3 (weights 1-2-1 per axis) over the pixel's class is
/// compared with each same-class 4-neighbour's; a jump above `SHADE_EDGE_PER_MILLE` of the
/// larger, floored at half the block's mean, marks the pixel; the marks then grow by one
/// pixel within the class. None unless `p.cycle_shade_edges` and the mean holds
/// `SHADE_EDGE_MIN_FRAMES` frames.
pub fn shade_edge_marks_cpu(p: &SortParams, means: &[f32], classes: &[u32]) -> Vec<bool> {
    let pixels = (p.width * p.height) as usize;
    let mut marks = vec![false; pixels];
    if p.cycle_shade_edges == 0 || p.cycle_mean_count < SHADE_EDGE_MIN_FRAMES {
        return marks;
    }
    let b = p.block as i64;
    let (bx, by) = crate::block_counts(p);
    for block in 0..bx * by {
        let px = crate::block_pixels(p, block);
        // In-block slot -> (pixel index, fixed mean, class); None off screen.
        let mut slot: Vec<Option<(usize, u32, u32)>> = vec![None; (b * b) as usize];
        for &(x, y, t) in &px {
            let i = (y * p.width + x) as usize;
            slot[t] = Some((i, shade_edge_fixed(means[i]), classes[i]));
        }
        let same = |t: usize, dx: i64, dy: i64| -> Option<usize> {
            let (tx, ty) = (t as i64 % b + dx, t as i64 / b + dy);
            if tx < 0 || ty < 0 || tx >= b || ty >= b {
                return None;
            }
            let q = (ty * b + tx) as usize;
            match (slot[t], slot[q]) {
                (Some((_, _, c)), Some((_, _, cq))) if c == cq => Some(q),
                _ => None,
            }
        };
        let (total, count) = px.iter().fold((0u64, 0u64), |(s, n), &(_, _, t)| {
            (s + u64::from(slot[t].map_or(0, |v| v.1)), n + 1)
        });
        let mut blur = vec![(0u64, 0u64); slot.len()];
        for &(_, _, t) in &px {
            let (mut sum, mut wt) = (0u64, 0u64);
            for dy in -1..=1i64 {
                for dx in -1..=1i64 {
                    if let Some(q) = same(t, dx, dy) {
                        let w = ((2 - dx.abs()) * (2 - dy.abs())) as u64;
                        sum += w * u64::from(slot[q].map_or(0, |v| v.1));
                        wt += w;
                    }
                }
            }
            blur[t] = (sum, wt);
        }
        let steps = [(1, 0), (-1, 0), (0, 1), (0, -1)];
        let scale = 2 * count;
        let mut raw = vec![false; slot.len()];
        for &(_, _, t) in &px {
            raw[t] = steps.iter().any(|&(dx, dy)| {
                same(t, dx, dy).is_some_and(|q| {
                    let (a, b) = (blur[t].0 * blur[q].1, blur[q].0 * blur[t].1);
                    let limit = (a.max(b) * scale).max(total * blur[t].1 * blur[q].1);
                    a.abs_diff(b) * scale * 1000 > limit * u64::from(SHADE_EDGE_PER_MILLE)
                })
            });
        }
        for &(_, _, t) in &px {
            let near = raw[t]
                || steps
                    .iter()
                    .any(|&(dx, dy)| same(t, dx, dy).is_some_and(|q| raw[q]));
            if let Some((i, _, _)) = slot[t] {
                marks[i] = near;
            }
        }
    }
    marks
}

/// What the sorting pass does with the marks (`shade_edge_marks_cpu`): marked pixels rank in
/// classes of their own (`classes` updated in place) and get `PRIMARY_SHADE_EDGE` in `flags`.
/// The pass never clears it: the trace rewrites every visible pixel's flags when it records
/// the primary hits (`TRACE_FLAG_RECORD_PRIMARY`, set for every method with the marks).
pub fn shade_edges_cpu(p: &SortParams, means: &[f32], classes: &mut [u32], flags: &mut [u32]) {
    let marks = shade_edge_marks_cpu(p, means, classes);
    for ((c, f), &m) in classes.iter_mut().zip(flags.iter_mut()).zip(&marks) {
        *c += if m { SHADE_EDGE_CLASS } else { 0 };
        *f |= if m { PRIMARY_SHADE_EDGE } else { 0 };
    }
}
