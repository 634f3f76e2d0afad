//! The report's chart: time against error, one labelled point per setting,
//! the Pareto front joined by a line. Drawn with `plotters` into an RGB
//! buffer and written with `image`; text uses a TrueType font read at run
//! time (`--font`).

use std::path::Path;

use anyhow::{anyhow, Context, Result};
use plotters::prelude::*;

use crate::report::Point;

const SIZE: (u32, u32) = (1200, 800);

pub(crate) fn draw(out: &Path, font: &Path, points: &[Point]) -> Result<()> {
    let bytes = std::fs::read(font).with_context(|| {
        format!("reading the chart font {} (pass --font with a .ttf file)", font.display())
    })?;
    plotters::style::register_font("sans-serif", FontStyle::Normal, Box::leak(bytes.into_boxed_slice()))
        .map_err(|_| anyhow!("{} is not a TrueType/OpenType font", font.display()))?;
    let mut buffer = vec![255u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, SIZE).into_drawing_area();
        plot(&root, points).map_err(|e| anyhow!("drawing the chart: {e}"))?;
        root.present().map_err(|e| anyhow!("drawing the chart: {e}"))?;
    }
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    image::save_buffer(out, &buffer, SIZE.0, SIZE.1, image::ColorType::Rgb8)
        .with_context(|| format!("writing {}", out.display()))
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

fn plot(root: &Area<'_>, points: &[Point]) -> Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let (t_lo, t_hi) = bounds(points.iter().map(|p| p.ms));
    let (_, e_hi) = bounds(points.iter().map(|p| p.rmse));
    let mut chart = ChartBuilder::on(root)
        .caption("zline: time against error (benchmark scenes)", ("sans-serif", 30))
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d((t_lo * 0.8..t_hi * 1.25).log_scale(), 0.0..e_hi * 1.1)?;
    chart
        .configure_mesh()
        .x_desc("total median frame time over the benchmark scenes, ms (log scale)")
        .y_desc("mean RMSE vs Phong 4x4 SSAA f64 truth, 8-bit steps")
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    let mut front: Vec<(f64, f64)> = points.iter().filter(|p| p.pareto).map(|p| (p.ms, p.rmse)).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart
        .draw_series(LineSeries::new(front, RGBColor(150, 150, 150).stroke_width(2)))?
        .label("Pareto front")
        .legend(|(x, y)| {
            PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(150, 150, 150).stroke_width(2))
        });
    for p in points {
        let color = if p.name.contains("adaptive") {
            RGBColor(200, 40, 40)
        } else if p.name.contains("ssaa") {
            RGBColor(40, 110, 200)
        } else {
            RGBColor(30, 30, 30)
        };
        chart.draw_series(std::iter::once(Circle::new((p.ms, p.rmse), 5, color.filled())))?;
        chart.draw_series(std::iter::once(Text::new(
            p.name.to_string(),
            (p.ms, p.rmse),
            ("sans-serif", 15).into_font().color(&color),
        )))?;
    }
    chart.configure_series_labels().border_style(BLACK).background_style(WHITE).draw()?;
    Ok(())
}

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo.is_finite() && lo > 0.0 {
        (lo, hi.max(lo * 1.01))
    } else {
        (0.1, hi.max(1.0))
    }
}
