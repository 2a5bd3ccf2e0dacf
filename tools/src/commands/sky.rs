//! `sky`: a procedural equirectangular sky (Radiance `.hdr`), the bundled environment map.
//! A blue gradient, a warm glow and a small bright sun above a grey ground: enough contrast
//! for sharp shadows and for importance sampling to matter, small enough to commit.

use std::path::PathBuf;

use anyhow::{Context, bail};
use blueshift_scene::{env_direction, env_uv};
use glam::{Vec2, Vec3};

/// `sky` flags.
#[derive(Debug, clap::Args)]
pub struct SkyArgs {
    /// Map width in texels (height is half of it).
    #[arg(long, default_value_t = 256)]
    pub width: u32,
    /// Sun elevation above the horizon, degrees.
    #[arg(long, default_value_t = 35.0, allow_negative_numbers = true)]
    pub sun_elevation: f32,
    /// Sun azimuth from -Z towards +X, degrees.
    #[arg(long, default_value_t = 150.0, allow_negative_numbers = true)]
    pub sun_azimuth: f32,
    /// Radiance of the sun disc (1.5 degrees in radius).
    #[arg(long, default_value_t = 1500.0)]
    pub sun_radiance: f32,
    /// Output `.hdr`.
    #[arg(long)]
    pub out: PathBuf,
}

/// Angular radius of the sun disc, degrees.
const SUN_RADIUS_DEG: f32 = 1.5;

/// The sun's direction for an elevation and an azimuth from -Z towards +X (degrees).
pub fn sun_direction(elevation_deg: f32, azimuth_deg: f32) -> Vec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    Vec3::new(a.sin() * e.cos(), e.sin(), -a.cos() * e.cos())
}

/// Sky radiance towards unit direction `d` (linear RGB).
pub fn sky_radiance(d: Vec3, sun: Vec3, sun_radiance: f32) -> Vec3 {
    let zenith = Vec3::new(0.18, 0.34, 0.85);
    let horizon = Vec3::new(0.85, 0.9, 1.0);
    let ground = Vec3::new(0.3, 0.27, 0.24) * 0.4;
    let t = (1.0 - d.y.max(0.0)).powi(3);
    let glow = Vec3::new(1.0, 0.85, 0.6) * 0.6 * (0.5 + 0.5 * d.dot(sun)).powi(16);
    let sky = zenith.lerp(horizon, t) + glow;
    // A soft horizon over 2 degrees below it.
    let below = ((-d.y) / 0.035).clamp(0.0, 1.0);
    let base = sky.lerp(ground, below * below * (3.0 - 2.0 * below));
    let in_sun = d.dot(sun) >= SUN_RADIUS_DEG.to_radians().cos();
    base + if in_sun {
        Vec3::new(1.0, 0.95, 0.85) * sun_radiance
    } else {
        Vec3::ZERO
    }
}

pub(crate) fn sky(a: &SkyArgs) -> anyhow::Result<()> {
    if !(8..=8192).contains(&a.width) || a.width % 2 != 0 {
        bail!("--width {} must be even and within 8..=8192", a.width);
    }
    if !(a.sun_radiance.is_finite() && a.sun_radiance >= 0.0) {
        bail!("--sun-radiance must be a finite number >= 0");
    }
    let (w, h) = (a.width, a.width / 2);
    let sun = sun_direction(a.sun_elevation, a.sun_azimuth);
    let r0 = Vec2::new(1.0, 0.0);
    let mut data = Vec::with_capacity((w * h * 3) as usize);
    for j in 0..h {
        for i in 0..w {
            // 4x4 supersampling keeps the sun disc's edge from aliasing.
            let mut sum = Vec3::ZERO;
            for k in 0..16 {
                let uv = Vec2::new(
                    (i as f32 + ((k % 4) as f32 + 0.5) / 4.0) / w as f32,
                    (j as f32 + ((k / 4) as f32 + 0.5) / 4.0) / h as f32,
                );
                sum += sky_radiance(env_direction(uv, r0), sun, a.sun_radiance);
            }
            data.extend_from_slice(&(sum / 16.0).to_array());
        }
    }
    debug_assert!(env_uv(Vec3::NEG_Z, r0).distance(Vec2::splat(0.5)) < 1e-6);
    let img = image::Rgb32FImage::from_raw(w, h, data).context("sky image size")?;
    let mut buf = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(img)
        .write_to(&mut buf, image::ImageFormat::Hdr)
        .context("encoding the sky as Radiance HDR")?;
    super::ensure_parent(&a.out)?;
    blueshift_assets::write_atomic(&a.out, buf.get_ref())?;
    println!("wrote {} ({w}x{h})", a.out.display());
    Ok(())
}
