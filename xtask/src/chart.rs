//! The report's chart: time against error, one labelled point per setting,
//! the Pareto front joined by a line. Drawn with `plotters` into an RGB
//! buffer and written with `image`; text uses a TrueType font read at run
//! time (`--font`).

use std::path::Path;

use anyhow::{anyhow, Context, Result};
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;

const SIZE: (u32, u32) = (1200, 800);

/// A setting's place on the chart: summed time and mean RMSE over the
/// benchmark scenes.
pub(crate) struct Point {
    pub(crate) name: String,
    pub(crate) ms: f64,
    pub(crate) rmse: f64,
    pub(crate) pareto: bool,
}

/// A chart's words: its title and the axes' descriptions.
pub(crate) struct Labels {
    pub(crate) title: &'static str,
    pub(crate) x: &'static str,
    pub(crate) y: &'static str,
    pub(crate) legend: &'static str,
    /// Time on a log axis (for times spanning orders of magnitude).
    pub(crate) log_time: bool,
}

/// The report's main chart.
pub(crate) const SETTINGS: Labels = Labels {
    title: "zline: time against error (benchmark scenes)",
    x: "total frame time over the benchmark scenes (fastest of N frames), ms",
    y: "mean RMSE vs the best image, 8-bit steps (log)",
    legend: "settings (grey line: Pareto front)",
    log_time: false,
};

pub(crate) fn draw(out: &Path, font: &Path, points: &[Point], labels: &Labels) -> Result<()> {
    register(font)?;
    let mut buffer = vec![255u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, SIZE).into_drawing_area();
        plot(&root, points, labels).map_err(|e| anyhow!("drawing the chart: {e}"))?;
        root.present().map_err(|e| anyhow!("drawing the chart: {e}"))?;
    }
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    image::save_buffer(out, &buffer, SIZE.0, SIZE.1, image::ColorType::Rgb8)
        .with_context(|| format!("writing {}", out.display()))
}

/// Registers the font once per process (both charts use it).
fn register(font: &Path) -> Result<()> {
    static DONE: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    if DONE.get().is_some() {
        return Ok(());
    }
    let bytes = std::fs::read(font).with_context(|| {
        format!("reading the chart font {} (pass --font with a .ttf file)", font.display())
    })?;
    plotters::style::register_font("sans-serif", FontStyle::Normal, Box::leak(bytes.into_boxed_slice()))
        .map_err(|_| anyhow!("{} is not a TrueType/OpenType font", font.display()))?;
    let _ = DONE.set(());
    Ok(())
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

fn plot(root: &Area<'_>, points: &[Point], labels: &Labels) -> Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let (plot_area, legend_area) = root.split_horizontally(SIZE.0 - 300);
    let (t_lo, t_hi) = bounds(points.iter().map(|p| p.ms));
    let (e_lo, e_hi) = bounds(points.iter().map(|p| p.rmse.max(1e-3)));
    if labels.log_time {
        let chart = ChartBuilder::on(&plot_area)
            .caption(labels.title, ("sans-serif", 28))
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d((t_lo * 0.7..t_hi * 1.4).log_scale(), (e_lo * 0.6..e_hi * 1.6).log_scale())?;
        series(chart, points, labels)?;
    } else {
        let chart = ChartBuilder::on(&plot_area)
            .caption(labels.title, ("sans-serif", 28))
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..t_hi * 1.1, (e_lo * 0.6..e_hi * 1.6).log_scale())?;
        series(chart, points, labels)?;
    }
    legend(&legend_area, points, labels)
}

/// The axes, the Pareto line and the numbered points.
fn series<X>(
    mut chart: ChartContext<'_, BitMapBackend<'_>, Cartesian2d<X, LogCoord<f64>>>,
    points: &[Point],
    labels: &Labels,
) -> Result<(), Box<dyn std::error::Error>>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(labels.x)
        .y_desc(labels.y)
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    let mut front: Vec<(f64, f64)> =
        points.iter().filter(|p| p.pareto).map(|p| (p.ms, p.rmse.max(1e-3))).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart.draw_series(LineSeries::new(front, RGBColor(150, 150, 150).stroke_width(2)))?;
    for (k, p) in points.iter().enumerate() {
        let color = color_of(p);
        let at = (p.ms, p.rmse.max(1e-3));
        chart.draw_series(std::iter::once(Circle::new(at, 5, color.filled())))?;
        // Numbers alternate above and below their point so neighbours with
        // equal error stay readable; the legend names them.
        let dy = if k % 2 == 0 { -22 } else { 6 };
        chart.draw_series(std::iter::once(
            EmptyElement::at(at)
                + Text::new(format!("{}", k + 1), (-4, dy), ("sans-serif", 15).into_font().color(&color)),
        ))?;
    }
    Ok(())
}

/// The legend: one numbered line per point.
fn legend(
    legend_area: &Area<'_>,
    points: &[Point],
    labels: &Labels,
) -> Result<(), Box<dyn std::error::Error>> {
    legend_area.draw(&Text::new(labels.legend, (10, 60), ("sans-serif", 16)))?;
    for (k, p) in points.iter().enumerate() {
        let y = 90 + 24 * k as i32;
        let mark = if p.pareto { " *" } else { "" };
        legend_area.draw(&Text::new(
            format!("{:>2}  {}{mark}", k + 1, p.name),
            (10, y),
            ("sans-serif", 16).into_font().color(&color_of(p)),
        ))?;
    }
    if points.iter().any(|p| p.pareto) {
        legend_area.draw(&Text::new(
            "* on the Pareto front",
            (10, 100 + 24 * points.len() as i32),
            ("sans-serif", 14),
        ))?;
    }
    Ok(())
}

fn color_of(p: &Point) -> RGBColor {
    if p.name.contains("adaptive") || p.name.contains("auto") {
        RGBColor(200, 40, 40)
    } else if p.name.contains("ssaa") || p.name.contains("map") {
        RGBColor(40, 110, 200)
    } else if p.name.contains("area") {
        RGBColor(30, 140, 60)
    } else {
        RGBColor(30, 30, 30)
    }
}

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo.is_finite() && lo > 0.0 {
        (lo, hi.max(lo * 1.01))
    } else {
        (0.1, hi.max(1.0))
    }
}
