//! A single-channel f32 image, luminance, image loading and atomic file writes.

use std::path::Path;

use crate::{Error, Result};

/// Rec.709 luminance of linear RGB: `Y = 0.2126 R + 0.7152 G + 0.0722 B`
/// (`blueshift_layout::REC709_LUMA`, shared with the shaders).
pub fn luminance(rgb: [f32; 3]) -> f32 {
    blueshift_layout::luminance(rgb)
}

/// A grayscale image, row-major: pixel `(x, y)` is `data[y * w + x]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Gray {
    /// Width in pixels.
    pub w: usize,
    /// Height in pixels.
    pub h: usize,
    /// `w * h` values, row-major.
    pub data: Vec<f32>,
}

impl Gray {
    /// Wraps `data`; fails unless `data.len() == w * h` and both sides are non-zero.
    pub fn new(w: usize, h: usize, data: Vec<f32>) -> Result<Self> {
        if w == 0 || h == 0 || data.len() != w * h {
            return Err(Error::Invalid(format!(
                "image {w}x{h} needs {} values, got {}",
                w * h,
                data.len()
            )));
        }
        Ok(Gray { w, h, data })
    }

    /// An image whose pixel `(x, y)` is `f(x, y)`.
    pub fn from_fn(w: usize, h: usize, mut f: impl FnMut(usize, usize) -> f32) -> Self {
        let mut data = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                data.push(f(x, y));
            }
        }
        Gray { w, h, data }
    }

    /// Luminance of interleaved linear RGB (`3 * w * h` values).
    pub fn from_rgb(w: usize, h: usize, rgb: &[f32]) -> Result<Self> {
        if rgb.len() != 3 * w * h {
            return Err(Error::Invalid(format!(
                "RGB image {w}x{h} needs {} values, got {}",
                3 * w * h,
                rgb.len()
            )));
        }
        let data = rgb
            .chunks_exact(3)
            .map(|p| luminance([p[0], p[1], p[2]]))
            .collect();
        Gray::new(w, h, data)
    }

    /// Pixel `(x, y)`; panics when out of range (callers index within `w`, `h`).
    pub fn at(&self, x: usize, y: usize) -> f32 {
        self.data[y * self.w + x]
    }

    /// Mean of all pixels.
    pub fn mean(&self) -> f64 {
        self.data.iter().map(|&v| f64::from(v)).sum::<f64>() / self.data.len() as f64
    }

    /// Pixel-wise `self - other` (e.g. error = estimate - reference).
    pub fn sub(&self, other: &Gray) -> Result<Gray> {
        if (self.w, self.h) != (other.w, other.h) {
            return Err(Error::Invalid(format!(
                "size mismatch: {}x{} vs {}x{}",
                self.w, self.h, other.w, other.h
            )));
        }
        let data = self
            .data
            .iter()
            .zip(&other.data)
            .map(|(a, b)| a - b)
            .collect();
        Gray::new(self.w, self.h, data)
    }

    /// Repeats the image `nx` times horizontally and `ny` times vertically.
    pub fn tiled(&self, nx: usize, ny: usize) -> Gray {
        Gray::from_fn(self.w * nx, self.h * ny, |x, y| {
            self.at(x % self.w, y % self.h)
        })
    }

    /// Loads a PNG (8 or 16 bit, gray or RGB(A); values scaled to [0, 1], no sRGB decoding)
    /// or an EXR (linear f32). Colour images are reduced with [`luminance`].
    pub fn load(path: &Path) -> Result<Gray> {
        let img = image::open(path).map_err(|source| match source {
            image::ImageError::IoError(e) => Error::io(path, e),
            source => Error::Image {
                path: path.to_path_buf(),
                source,
            },
        })?;
        let (w, h) = (img.width() as usize, img.height() as usize);
        if img.color().has_color() {
            let rgb = img.into_rgb32f();
            Gray::from_rgb(w, h, rgb.as_raw())
        } else {
            let l = img.to_luma32f();
            Gray::new(w, h, l.into_raw())
        }
    }
}

impl From<&blueshift_assets::Mask> for Gray {
    /// The mask as an image of `rank / (n^2 - 1)` in [0, 1].
    fn from(mask: &blueshift_assets::Mask) -> Self {
        let n = mask.n;
        let m = (n * n - 1) as f32;
        Gray::from_fn(n, n, |x, y| f32::from(mask.ranks[y * n + x]) / m)
    }
}

/// Encodes `img` as PNG in memory and writes it with [`blueshift_assets::write_atomic`].
pub(crate) fn save_image(img: &image::DynamicImage, path: &Path) -> Result<()> {
    let mut buf = std::io::Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Png)
        .map_err(|source| Error::Image {
            path: path.to_path_buf(),
            source,
        })?;
    blueshift_assets::write_atomic(path, buf.get_ref()).map_err(|e| match e {
        blueshift_assets::AssetError::Io { path, source } => Error::Io { path, source },
        other => Error::Invalid(other.to_string()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mask_to_gray_scales_ranks_to_unit_range() {
        let m = blueshift_assets::Mask::new(2, vec![3, 1, 0, 2]).unwrap();
        let g = Gray::from(&m);
        assert_eq!((g.w, g.h), (2, 2));
        assert_eq!(g.data, vec![1.0, 1.0 / 3.0, 0.0, 2.0 / 3.0]);
    }

    #[test]
    fn luminance_weights_sum_to_one() {
        assert!((luminance([1.0, 1.0, 1.0]) - 1.0).abs() < 1e-6);
        assert!((luminance([0.0, 1.0, 0.0]) - 0.7152).abs() < 1e-6);
    }

    #[test]
    fn new_rejects_wrong_length() {
        assert!(Gray::new(2, 2, vec![0.0; 3]).is_err());
    }

    #[test]
    fn png_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("g.png");
        let g = Gray::from_fn(5, 3, |x, y| (x + 5 * y) as f32 / 14.0);
        let bytes = g.data.iter().map(|v| (v * 255.0).round() as u8).collect();
        let img = image::GrayImage::from_raw(5, 3, bytes).unwrap();
        save_image(&image::DynamicImage::ImageLuma8(img), &p).unwrap();
        let back = Gray::load(&p).unwrap();
        assert_eq!((back.w, back.h), (5, 3));
        for (a, b) in g.data.iter().zip(&back.data) {
            assert!((a - b).abs() < 1.0 / 255.0);
        }
    }

    #[test]
    fn missing_file_is_an_io_error() {
        let e = Gray::load(Path::new("/nonexistent/x.png")).unwrap_err();
        assert!(e.to_string().contains("/nonexistent/x.png"), "{e}");
    }
}
