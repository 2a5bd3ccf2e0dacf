//! The texture atlas: the scene's images end to end, one RGBA8 word per texel, read from the
//! scene's own pixels when the upload writes them. The GPU form shares the images with the
//! scene (an `Arc`) instead of repacking them: a scene with 2^25 texture texels held 128 MiB
//! more on the host while its images were written.

use crate::scene::Image;
use std::sync::Arc;

/// The scene's images as one array of `u32` words (`u32::from_le_bytes` of each RGBA8 texel),
/// image `i` from word [`Atlas::offset`]`(i)`.
#[derive(Clone, Debug, Default)]
pub struct Atlas {
    images: Arc<[Image]>,
    /// The word where each image starts, then the total.
    starts: Vec<usize>,
}

impl Atlas {
    pub fn new(images: Arc<[Image]>) -> Self {
        let mut starts = Vec::with_capacity(images.len() + 1);
        let mut at = 0;
        starts.push(at);
        for img in images.iter() {
            at += img.rgba8.len() / 4;
            starts.push(at);
        }
        Atlas { images, starts }
    }

    /// Words in the atlas (texture texels of the scene).
    pub fn len(&self) -> usize {
        self.starts.last().copied().unwrap_or(0)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The word where image `i` starts.
    pub fn offset(&self, i: usize) -> Option<usize> {
        self.starts
            .get(i)
            .filter(|_| i < self.images.len())
            .copied()
    }

    /// Writes words `first .. first + out.len()` into `out`, zeros past the end.
    pub fn write(&self, first: usize, out: &mut [u32]) {
        out.fill(0);
        // The image that holds word `first` (the last one starting at or before it).
        let mut i = self
            .starts
            .partition_point(|&s| s <= first)
            .saturating_sub(1);
        let mut k = 0;
        while k < out.len() && i < self.images.len() {
            let at = (first + k).saturating_sub(self.starts[i]) * 4;
            let bytes = self.images[i].rgba8.get(at..).unwrap_or(&[]);
            for (w, c) in out[k..].iter_mut().zip(bytes.chunks_exact(4)) {
                *w = u32::from_le_bytes([c[0], c[1], c[2], c[3]]);
                k += 1;
            }
            i += 1;
        }
    }

    /// The whole atlas (tests; an upload writes it a range at a time).
    pub fn to_vec(&self) -> Vec<u32> {
        let mut v = vec![0; self.len()];
        self.write(0, &mut v);
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(words: &[u32]) -> Image {
        Image {
            name: None,
            width: words.len() as u32,
            height: 1,
            rgba8: words.iter().flat_map(|w| w.to_le_bytes()).collect(),
        }
    }

    #[test]
    fn every_range_reads_the_images_end_to_end() {
        // Images of 3, 0, 1 and 4 texels: ranges that start, end and cross between them.
        let words: [&[u32]; 4] = [&[1, 2, 3], &[], &[4], &[5, 6, 7, 8]];
        let atlas = Atlas::new(words.iter().map(|w| image(w)).collect());
        let all: Vec<u32> = words.concat();
        assert_eq!((atlas.len(), atlas.to_vec()), (8, all.clone()));
        assert_eq!(
            (0..5).map(|i| atlas.offset(i)).collect::<Vec<_>>(),
            [Some(0), Some(3), Some(3), Some(4), None]
        );
        for first in 0..10 {
            for n in 0..10 {
                let mut out = vec![u32::MAX; n];
                atlas.write(first, &mut out);
                let want: Vec<u32> = (first..first + n)
                    .map(|k| all.get(k).copied().unwrap_or(0))
                    .collect();
                assert_eq!(out, want, "words {first} + {n}");
            }
        }
        assert!(Atlas::default().is_empty() && Atlas::new(Arc::new([])).to_vec().is_empty());
    }
}
