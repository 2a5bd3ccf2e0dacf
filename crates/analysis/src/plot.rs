//! PNG pictures: DC-centred spectra and radial-profile charts.
//!
//! Charts use plotters' default text stack (font-kit + fontconfig, "sans-serif", i.e.
//! DejaVu Sans from fonts-dejavu-core). If no font can be loaded at run time the chart is
//! drawn again without any text rather than failing.

use std::path::Path;

use plotters::prelude::*;

use crate::gray::save_image;
use crate::{Error, LF_CUTOFF, Result, Spectrum};

/// Log-scale grayscale picture of a DC-centred spectrum: white at the largest non-DC power,
/// black `decades` decades below it (and at DC). Each bin becomes a square of
/// `max(1, min_size / n)` pixels.
pub fn spectrum_to_image(s: &Spectrum, decades: f64, min_size: usize) -> image::GrayImage {
    let n = s.n;
    let dc = (n / 2) * n + n / 2;
    let max = s
        .power
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != dc)
        .map(|(_, p)| *p)
        .fold(0.0f64, f64::max);
    let lo = max * 10f64.powf(-decades.max(0.1));
    let scale = (min_size / n).max(1);
    let side = (n * scale) as u32;
    image::GrayImage::from_fn(side, side, |x, y| {
        let (bx, by) = (x as usize / scale, y as usize / scale);
        let i = by * n + bx;
        if i == dc || max <= 0.0 {
            return image::Luma([0]);
        }
        let p = s.power[i].max(lo);
        let t = ((p / lo).log10() / (max / lo).log10()).clamp(0.0, 1.0);
        image::Luma([(t * 255.0).round() as u8])
    })
}

/// Writes [`spectrum_to_image`] (3 decades, at least 256 px) as a PNG.
pub fn save_spectrum_png(s: &Spectrum, path: &Path) -> Result<()> {
    let img = spectrum_to_image(s, 3.0, 256);
    save_image(&image::DynamicImage::ImageLuma8(img), path)
}

/// One named curve of a radial-profile chart.
#[derive(Clone, Debug)]
pub struct RadialSeries {
    /// Legend entry.
    pub name: String,
    /// Frequencies in cycles/pixel.
    pub freq: Vec<f64>,
    /// Power at each frequency.
    pub power: Vec<f64>,
}

/// Draws several radial profiles on one chart (x: cycles/pixel from 0 to 0.5, linear power,
/// a gray marker at the `LF` cut-off) with a legend, and writes it as an 800x500 PNG.
/// The DC bin (frequency 0) is skipped.
pub fn plot_radial_profiles(series: &[RadialSeries], title: &str, path: &Path) -> Result<()> {
    let (w, h) = (800u32, 500u32);
    let mut buf = vec![0u8; (w * h * 3) as usize];
    if draw_chart(&mut buf, (w, h), series, title, true).is_err() {
        buf.iter_mut().for_each(|b| *b = 0);
        draw_chart(&mut buf, (w, h), series, title, false).map_err(Error::Plot)?;
    }
    let img = image::RgbImage::from_raw(w, h, buf)
        .ok_or_else(|| Error::Plot("chart buffer size".into()))?;
    save_image(&image::DynamicImage::ImageRgb8(img), path)
}

fn draw_chart(
    buf: &mut [u8],
    size: (u32, u32),
    series: &[RadialSeries],
    title: &str,
    text: bool,
) -> std::result::Result<(), String> {
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let ymax = series
        .iter()
        .flat_map(|s| s.freq.iter().zip(&s.power))
        .filter(|(f, p)| **f > 0.0 && p.is_finite())
        .map(|(_, p)| *p)
        .fold(0.0f64, f64::max)
        .max(1e-30)
        * 1.1;
    let root = BitMapBackend::with_buffer(buf, size).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let mut builder = ChartBuilder::on(&root);
    builder.margin(15);
    if text {
        builder
            .caption(title, ("sans-serif", 22))
            .x_label_area_size(45)
            .y_label_area_size(70);
    }
    let mut chart = builder
        .build_cartesian_2d(0f64..0.5f64, 0f64..ymax)
        .map_err(|x| e(&x))?;
    let mut mesh = chart.configure_mesh();
    if text {
        mesh.x_desc("frequency (cycles/pixel)").y_desc("power");
    } else {
        mesh.x_labels(0).y_labels(0);
    }
    mesh.draw().map_err(|x| e(&x))?;
    chart
        .draw_series(LineSeries::new(
            [(LF_CUTOFF, 0.0), (LF_CUTOFF, ymax)],
            RGBColor(170, 170, 170),
        ))
        .map_err(|x| e(&x))?;
    for (i, s) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let pts: Vec<(f64, f64)> = s
            .freq
            .iter()
            .zip(&s.power)
            .filter(|(f, p)| **f > 0.0 && p.is_finite())
            .map(|(f, p)| (*f, *p))
            .collect();
        let drawn = chart
            .draw_series(LineSeries::new(pts, color.stroke_width(2)))
            .map_err(|x| e(&x))?;
        if text {
            drawn.label(s.name.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        }
    }
    if text {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|x| e(&x))?;
    }
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radial::tests::white_noise;
    use crate::{periodogram, radial_profile};

    #[test]
    fn writes_spectrum_and_profile_pngs() {
        let dir = tempfile::tempdir().unwrap();
        let s = periodogram(&white_noise(64, 64, 1)).unwrap();
        let p = dir.path().join("s.png");
        save_spectrum_png(&s, &p).unwrap();
        let img = image::open(&p).unwrap();
        assert_eq!((img.width(), img.height()), (256, 256));
        let r = radial_profile(&s);
        let series = vec![RadialSeries {
            name: "white".into(),
            freq: r.freq.clone(),
            power: r.power.clone(),
        }];
        let q = dir.path().join("r.png");
        plot_radial_profiles(&series, "test", &q).unwrap();
        assert_eq!(image::open(&q).unwrap().width(), 800);
    }
}
