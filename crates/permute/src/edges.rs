//! CPU twin of shaders/permute/classify_pixels.comp (edge-aware grouping).
use crate::SortParams;
use crate::similar::similar;
use blueshift_layout::motion::GBufferTexel;

/// Per visible pixel (row-major, `width * height`): the in-block index (among the block's
/// visible pixels, row-major) of its class leader. Leader clustering: a pixel joins the first
/// earlier leader of its block it is similar to, else it leads a class.
pub fn classify_pixels_cpu(p: &SortParams, gbuffer: &[GBufferTexel]) -> Vec<u32> {
    let mut classes = vec![0u32; (p.width * p.height) as usize];
    let (bx, by) = crate::block_counts(p);
    for block in 0..bx * by {
        let at: Vec<usize> = crate::block_pixels(p, block)
            .into_iter()
            .map(|(x, y, _)| (y * p.width + x) as usize)
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
    classes
}
