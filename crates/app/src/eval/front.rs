//! The per-frame against accumulated trade-off: per method, P1 of single frames against P1 of
//! their accumulation along the motion (TAA, the EMA for a still camera; both on emitter-free
//! pixels, ratios to white), as a table and a scatter plot. No method is best at both
//! everywhere, so the report shows where each one sits.
use super::ratios::{ratio, white_of};
use super::{Config, Run};
use anyhow::{Context, Result};
use image::RgbImage;
use plotters::prelude::*;
use std::path::Path;

/// One method's point: geometric means over the configurations of its ratios to white.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontPoint {
    pub method: String,
    pub per_frame: f64,
    pub taa: f64,
}

/// Geometric means over `configs` of each method's (per-frame P1, TAA P1) ratios, emitter-free
/// pixels, in the order the methods first appear; methods missing from a configuration are
/// averaged over the ones they ran in.
pub fn front_points(configs: &[Config], runs: &[Run]) -> Vec<FrontPoint> {
    let mut acc: Vec<(String, f64, f64, u32)> = Vec::new();
    for c in configs {
        let Some(white) = white_of(runs, c) else {
            continue;
        };
        for r in runs.iter().filter(|r| &r.config == c) {
            let (m, w) = (&r.metrics, &white.metrics);
            let p1 = ratio(m.raw.p1.clean, w.raw.p1.clean);
            let taa = ratio(m.taa.p1.clean, w.taa.p1.clean);
            if !(p1 > 0.0 && taa > 0.0) {
                continue;
            }
            let name = r.method.name();
            let i = match acc.iter().position(|a| a.0 == name) {
                Some(i) => i,
                None => {
                    acc.push((name, 0.0, 0.0, 0));
                    acc.len() - 1
                }
            };
            acc[i].1 += p1.ln();
            acc[i].2 += taa.ln();
            acc[i].3 += 1;
        }
    }
    acc.into_iter()
        .map(|(method, a, b, n)| FrontPoint {
            method,
            per_frame: (a / f64::from(n)).exp(),
            taa: (b / f64::from(n)).exp(),
        })
        .collect()
}

/// Scatter plot of `points` (lower left is better on both axes).
pub fn plot(points: &[FrontPoint], title: &str, path: &Path) -> Result<()> {
    let (w, h) = (800u32, 560u32);
    let mut buf = vec![255u8; (w * h * 3) as usize];
    draw(&mut buf, (w, h), points, title).map_err(|e| anyhow::anyhow!("front plot: {e}"))?;
    let img = RgbImage::from_raw(w, h, buf).context("front plot buffer")?;
    super::figures::save(&img, path)
}

fn draw(
    buf: &mut [u8],
    size: (u32, u32),
    points: &[FrontPoint],
    title: &str,
) -> Result<(), String> {
    let root = BitMapBackend::with_buffer(buf, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let hi = |f: fn(&FrontPoint) -> f64| points.iter().map(f).fold(1.05f64, f64::max).min(3.0);
    let lo = |f: fn(&FrontPoint) -> f64| points.iter().map(f).fold(1.0f64, f64::min) - 0.05;
    let (x0, x1) = (lo(|p| p.per_frame).max(0.0), hi(|p| p.per_frame) + 0.05);
    let (y0, y1) = (lo(|p| p.taa).max(0.0), hi(|p| p.taa) + 0.05);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc("per-frame P1 / white (emitter-free)")
        .y_desc("TAA P1 / white (emitter-free)")
        .draw()
        .map_err(|e| e.to_string())?;
    for (i, p) in points.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let (x, y) = (p.per_frame.min(x1), p.taa.min(y1));
        chart
            .draw_series([Circle::new((x, y), 6, color.filled())])
            .map_err(|e| e.to_string())?;
        chart
            .draw_series([Text::new(
                p.method.clone(),
                (x, y),
                ("sans-serif", 15).into_font().color(&BLACK),
            )])
            .map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plot_writes_a_png() {
        let dir = std::env::temp_dir().join(format!("blueshift-front-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("front.png");
        let pts = [
            FrontPoint {
                method: "a".into(),
                per_frame: 0.7,
                taa: 0.9,
            },
            FrontPoint {
                method: "b".into(),
                per_frame: 1.0,
                taa: 0.5,
            },
        ];
        plot(&pts, "front", &p).unwrap();
        let img = image::open(&p).unwrap();
        assert_eq!((img.width(), img.height()), (800, 560));
        std::fs::remove_dir_all(&dir).ok();
    }
}
