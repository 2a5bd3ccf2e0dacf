//! CPU twin of shaders/permute/classify_pixels.comp (edge-aware grouping).
use crate::SortParams;
use crate::similar::similar;
use blueshift_layout::motion::GBufferTexel;

/// Per visible pixel (row-major, `width * height`): the in-block index (among the block's
/// visible pixels, row-major) of its class leader. Leader clustering: a pixel joins the first
/// earlier leader of its block it is similar to, else it leads a class.
pub fn classify_pixels_cpu(p: &SortParams, gbuffer: &[GBufferTexel]) -> Vec<u32> {
    let b = p.block;
    let mut classes = vec![0u32; (p.width * p.height) as usize];
    for by in (0..p.height).step_by(b as usize) {
        for bx in (0..p.width).step_by(b as usize) {
            let at: Vec<usize> = (0..b * b)
                .map(|k| (bx + k % b, by + k / b))
                .filter(|&(x, y)| x < p.width && y < p.height)
                .map(|(x, y)| (y * p.width + x) as usize)
                .collect();
            let mut leader: Vec<usize> = Vec::with_capacity(at.len());
            for (a, &pa) in at.iter().enumerate() {
                let cls = (0..a)
                    .find(|&j| leader[j] == j && similar(&gbuffer[pa], &gbuffer[at[j]]))
                    .unwrap_or(a);
                leader.push(cls);
                classes[pa] = cls as u32;
            }
        }
    }
    classes
}
