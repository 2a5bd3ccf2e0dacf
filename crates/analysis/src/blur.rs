//! Gaussian blur and the perceptual error `P_s` (docs/results.md, "How the numbers are measured").

use crate::{Error, Gray, Result};

/// How the blur reads outside the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// Wrap around (periodic tiles, masks).
    Toroidal,
    /// Repeat the edge pixel (rendered images; the default for `P_s` of renders).
    Clamp,
}

/// Sampled Gaussian `exp(-i^2 / (2 sigma^2))` for `i` in `-r..=r`, `r = ceil(4 sigma)`,
/// normalised to sum 1. `sigma <= 0` gives the identity kernel `[1]`.
pub fn gaussian_kernel(sigma: f64) -> Vec<f64> {
    if sigma.is_nan() || sigma <= 0.0 {
        return vec![1.0];
    }
    let r = (4.0 * sigma).ceil() as i64;
    let k: Vec<f64> = (-r..=r)
        .map(|i| (-(i * i) as f64 / (2.0 * sigma * sigma)).exp())
        .collect();
    let s: f64 = k.iter().sum();
    k.into_iter().map(|v| v / s).collect()
}

fn blur_1d(src: &[f64], dst: &mut [f64], len: usize, stride: usize, k: &[f64], b: Boundary) {
    let r = (k.len() / 2) as i64;
    let n = len as i64;
    for i in 0..n {
        let mut acc = 0.0;
        for (j, kv) in k.iter().enumerate() {
            let p = i + j as i64 - r;
            let p = match b {
                Boundary::Toroidal => p.rem_euclid(n),
                Boundary::Clamp => p.clamp(0, n - 1),
            };
            acc += kv * src[p as usize * stride];
        }
        dst[i as usize * stride] = acc;
    }
}

/// Separable Gaussian blur with standard deviation `sigma` pixels (kernel of
/// [`gaussian_kernel`]), computed in f64.
pub fn gaussian_blur(img: &Gray, sigma: f64, boundary: Boundary) -> Result<Gray> {
    if !sigma.is_finite() || sigma < 0.0 {
        return Err(Error::Invalid(format!("blur sigma {sigma}")));
    }
    let k = gaussian_kernel(sigma);
    let (w, h) = (img.w, img.h);
    let src: Vec<f64> = img.data.iter().map(|&v| f64::from(v)).collect();
    let mut tmp = vec![0.0; w * h];
    for y in 0..h {
        blur_1d(&src[y * w..], &mut tmp[y * w..], w, 1, &k, boundary);
    }
    let mut out = vec![0.0; w * h];
    for x in 0..w {
        blur_1d(&tmp[x..], &mut out[x..], h, w, &k, boundary);
    }
    Gray::new(w, h, out.into_iter().map(|v| v as f32).collect())
}

/// Root mean square of an error image (no mean removed).
pub fn rmse(err: &Gray) -> f64 {
    let s: f64 = err.data.iter().map(|&v| f64::from(v) * f64::from(v)).sum();
    (s / err.data.len() as f64).sqrt()
}

/// `P_s`: RMSE of the error blurred with a Gaussian of standard deviation `sigma` pixels.
pub fn blurred_rmse(err: &Gray, sigma: f64, boundary: Boundary) -> Result<f64> {
    Ok(rmse(&gaussian_blur(err, sigma, boundary)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radial::tests::white_noise;

    #[test]
    fn blurred_white_noise_rmse_matches_theory() {
        // White noise of std 1 blurred with a 2D Gaussian keeps std 1 / (2 sqrt(pi) sigma).
        // 512^2 pixels, toroidal; tolerance 3% (sampling error ~1% at sigma 2).
        let mut img = white_noise(512, 512, 21);
        for v in &mut img.data {
            *v *= 12f32.sqrt();
        }
        assert!((rmse(&img) - 1.0).abs() < 0.01);
        for sigma in [1.0, 2.0] {
            let p = blurred_rmse(&img, sigma, Boundary::Toroidal).unwrap();
            let expect = 1.0 / (2.0 * std::f64::consts::PI.sqrt() * sigma);
            assert!(
                (p / expect - 1.0).abs() < 0.03,
                "sigma {sigma}: {p} vs {expect}"
            );
        }
    }

    #[test]
    fn blur_preserves_constants_and_mean() {
        let img = Gray::from_fn(13, 7, |_, _| 0.25);
        for b in [Boundary::Toroidal, Boundary::Clamp] {
            let o = gaussian_blur(&img, 2.0, b).unwrap();
            assert!(o.data.iter().all(|v| (v - 0.25).abs() < 1e-6));
        }
        let n = white_noise(32, 16, 2);
        let o = gaussian_blur(&n, 3.0, Boundary::Toroidal).unwrap();
        assert!((o.mean() - n.mean()).abs() < 1e-6);
    }

    #[test]
    fn zero_sigma_is_identity_and_negative_is_an_error() {
        let n = white_noise(8, 8, 1);
        assert_eq!(gaussian_blur(&n, 0.0, Boundary::Clamp).unwrap(), n);
        assert!(gaussian_blur(&n, -1.0, Boundary::Clamp).is_err());
    }
}
