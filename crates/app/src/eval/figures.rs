//! Report figures: signed error crops beside their spectra, radial curves of all methods,
//! P1 ratio over frames, a strip of rendered frames; and the display tonemap they and FLIP
//! share.
use super::Run;
use anyhow::{Context, Result};
use blueshift_analysis::{RadialSeries, plot_radial_profiles, spectrum_to_image};
use image::{Rgb, RgbImage};
use plotters::prelude::*;
use std::path::Path;

fn srgb8(v: f32) -> u8 {
    let c = v.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// Linear RGB to sRGB8 as shown on screen: exposure 1, every channel clamped at 1 (as
/// shaders/image/tonemap.comp at its default exposure; `masks::DISPLAY_WHITE` depends on it).
pub fn tonemap(px: &[[f32; 4]]) -> Vec<u8> {
    px.iter()
        .flat_map(|p| [srgb8(p[0]), srgb8(p[1]), srgb8(p[2])])
        .collect()
}

/// Blue (negative) - white (0) - red (positive), saturating at +-`scale`.
fn signed_color(v: f32, scale: f32) -> Rgb<u8> {
    let t = (v / scale).clamp(-1.0, 1.0);
    let a = (255.0 * (1.0 - t.abs())) as u8;
    if t >= 0.0 {
        Rgb([255, a, a])
    } else {
        Rgb([a, a, 255])
    }
}

/// The error crop (centre, at most 128x128, 2x zoom) beside the window-averaged spectrum.
pub fn error_and_spectrum(run: &Run, path: &Path) -> Result<()> {
    let e = run.last_error.as_ref().context("no error image")?;
    let c = 128.min(e.w).min(e.h);
    let (x0, y0) = ((e.w - c) / 2, (e.h - c) / 2);
    let rms = (e.data.iter().map(|v| v * v).sum::<f32>() / e.data.len() as f32)
        .sqrt()
        .max(1e-6);
    let spec = run
        .metrics
        .spectrum
        .as_ref()
        .map(|s| spectrum_to_image(s, 3.0, 256));
    let side = 2 * c as u32;
    let sw = spec.as_ref().map_or(0, |s| s.width());
    let mut img = RgbImage::from_pixel(
        side + 8 + sw,
        side.max(spec.as_ref().map_or(0, |s| s.height())),
        Rgb([40, 40, 40]),
    );
    for y in 0..side {
        for x in 0..side {
            let v = e.at(x0 + x as usize / 2, y0 + y as usize / 2);
            img.put_pixel(x, y, signed_color(v, 2.5 * rms));
        }
    }
    if let Some(s) = spec {
        for (x, y, p) in s.enumerate_pixels() {
            img.put_pixel(side + 8 + x, y, Rgb([p.0[0]; 3]));
        }
    }
    save(&img, path)
}

/// Last raw frames of all runs of one configuration side by side (tonemapped).
pub fn strip(runs: &[&Run], w: u32, h: u32, path: &Path) -> Result<()> {
    let mut img = RgbImage::from_pixel((w + 4) * runs.len() as u32, h, Rgb([0, 0, 0]));
    for (i, run) in runs.iter().enumerate() {
        let rgb = tonemap(&run.last_frame);
        for y in 0..h {
            for x in 0..w {
                let k = ((y * w + x) * 3) as usize;
                img.put_pixel(
                    i as u32 * (w + 4) + x,
                    y,
                    Rgb([rgb[k], rgb[k + 1], rgb[k + 2]]),
                );
            }
        }
    }
    save(&img, path)
}

/// Radial spectra of all runs of one configuration.
pub fn radial(runs: &[&Run], title: &str, path: &Path) -> Result<()> {
    let series: Vec<RadialSeries> = runs
        .iter()
        .filter_map(|r| {
            r.metrics.radial.as_ref().map(|p| RadialSeries {
                name: r.method.name().to_string(),
                freq: p.freq.clone(),
                power: p.power.clone(),
            })
        })
        .collect();
    if series.is_empty() {
        return Ok(()); // images smaller than one spectrum tile
    }
    plot_radial_profiles(&series, title, path)?;
    Ok(())
}

/// P1(method) / P1(white) on emitter-free pixels per frame, one line per method (the headline
/// pixel set: with jitter, all-pixel P1 follows the aliasing at the lights' edges).
pub fn p1_over_frames(runs: &[&Run], title: &str, path: &Path) -> Result<()> {
    let Some(white) = runs
        .iter()
        .find(|r| r.method == blueshift_render::Method::White)
    else {
        return Ok(());
    };
    let lines: Vec<(String, Vec<f64>)> = runs
        .iter()
        .filter(|r| r.method != blueshift_render::Method::White)
        .map(|r| {
            let v = r
                .metrics
                .p1_clean_per_frame
                .iter()
                .zip(&white.metrics.p1_clean_per_frame)
                .map(|(a, b)| a / b.max(1e-12))
                .collect();
            (r.method.name().to_string(), v)
        })
        .collect();
    let (w, h) = (800u32, 450u32);
    let mut buf = vec![255u8; (w * h * 3) as usize];
    if draw_lines(&mut buf, (w, h), &lines, title, true).is_err() {
        buf.iter_mut().for_each(|b| *b = 255);
        draw_lines(&mut buf, (w, h), &lines, title, false)
            .map_err(|e| anyhow::anyhow!("plot: {e}"))?;
    }
    save(&RgbImage::from_raw(w, h, buf).context("plot buffer")?, path)
}

fn draw_lines(
    buf: &mut [u8],
    size: (u32, u32),
    lines: &[(String, Vec<f64>)],
    title: &str,
    text: bool,
) -> Result<(), String> {
    let root = BitMapBackend::with_buffer(buf, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let frames = lines.iter().map(|l| l.1.len()).max().unwrap_or(1).max(2);
    let ymax = lines
        .iter()
        .flat_map(|l| l.1.iter().copied())
        .fold(1.2f64, f64::max)
        .min(3.0);
    let mut b = ChartBuilder::on(&root);
    b.margin(15);
    if text {
        b.caption(title, ("sans-serif", 20))
            .x_label_area_size(35)
            .y_label_area_size(50);
    }
    let mut chart = b
        .build_cartesian_2d(0f64..(frames - 1) as f64, 0f64..ymax)
        .map_err(|e| e.to_string())?;
    if text {
        chart
            .configure_mesh()
            .x_desc("frame")
            .y_desc("P1 / P1(white), emitter-free pixels")
            .draw()
            .map_err(|e| e.to_string())?;
    }
    for (i, (name, v)) in lines.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let s = chart
            .draw_series(LineSeries::new(
                v.iter().enumerate().map(|(x, &y)| (x as f64, y.min(ymax))),
                color.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?;
        if text {
            s.label(name.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
        }
    }
    if text {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())?;
    Ok(())
}

/// Writes `img` as PNG, atomically.
pub(super) fn save(img: &RgbImage, path: &Path) -> Result<()> {
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)?;
    Ok(crate::output::write_atomic(path, &out.into_inner())?)
}
