//! `cargo xtask report`: speed against error. Every setting that trades one
//! for the other renders every report scene; each image is timed (fastest and median of
//! several frames) and compared with two f64 truths from `zline-truth`:
//! the best image (Phong, perspective-correct, 16 samples per pixel) and the
//! truth of the setting's own model (same shading, interpolation and
//! sampling). Writes a markdown table and a chart of time against error.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use zline::scene::{DepthMode, Interpolation, RenderSettings, Scene, ShadingMode};
use zline::scenes::hard_cases;
use zline_truth::{render_truth, ErrorStats, TruthImage};

use crate::chart::Point;
use crate::timing::time_interleaved;

/// Where the report's inputs and outputs go.
pub(crate) struct Args {
    pub(crate) assets: PathBuf,
    pub(crate) out: PathBuf,
    pub(crate) chart: PathBuf,
    pub(crate) frames: usize,
    pub(crate) size: (u32, u32),
    pub(crate) filter: Option<String>,
    pub(crate) font: PathBuf,
}

/// One setting: a name and what it changes.
#[derive(Clone, Copy, Debug)]
struct Setting {
    name: &'static str,
    shading: ShadingMode,
    interpolation: Interpolation,
    adaptive: Option<f32>,
    ssaa: u32,
    depth: DepthMode,
}

impl Setting {
    const fn new(name: &'static str, shading: ShadingMode, interpolation: Interpolation) -> Setting {
        Setting { name, shading, interpolation, adaptive: None, ssaa: 1, depth: DepthMode::Normalized }
    }

    fn apply(&self, s: &mut RenderSettings) {
        s.shading = self.shading;
        s.interpolation = self.interpolation;
        s.adaptive_tolerance = self.adaptive;
        s.ssaa = self.ssaa;
        s.depth = self.depth;
    }

    /// The truth of this setting's own model: same shading, interpolation
    /// and samples (adaptive and depth encodings are the fast renderer's
    /// choices; their model is the base mode's).
    fn model(&self) -> (ShadingMode, Interpolation, u32) {
        (self.shading, self.interpolation, self.ssaa)
    }
}

const PERSPECTIVE: Interpolation = Interpolation::PerspectiveCorrect;
const LINEAR: Interpolation = Interpolation::ScreenLinear;

fn settings() -> Vec<Setting> {
    use ShadingMode::{Flat, Gouraud, Phong};
    let adaptive =
        |name, shading, tol| Setting { adaptive: Some(tol), ..Setting::new(name, shading, PERSPECTIVE) };
    vec![
        Setting::new("flat", Flat, PERSPECTIVE),
        Setting::new("gouraud", Gouraud, PERSPECTIVE),
        Setting::new("gouraud linear", Gouraud, LINEAR),
        adaptive("gouraud adaptive 0.5", Gouraud, 0.5),
        adaptive("gouraud adaptive 2", Gouraud, 2.0),
        adaptive("gouraud adaptive 8", Gouraud, 8.0),
        Setting::new("phong", Phong, PERSPECTIVE),
        Setting::new("phong linear", Phong, LINEAR),
        adaptive("phong adaptive 0.5", Phong, 0.5),
        adaptive("phong adaptive 2", Phong, 2.0),
        adaptive("phong adaptive 8", Phong, 8.0),
        Setting { depth: DepthMode::ReversedFloat, ..Setting::new("phong reversed-z", Phong, PERSPECTIVE) },
        Setting { ssaa: 2, ..Setting::new("phong ssaa 2x2", Phong, PERSPECTIVE) },
        Setting { ssaa: 4, ..Setting::new("phong ssaa 4x4", Phong, PERSPECTIVE) },
    ]
}

/// The best image: Phong, perspective-correct, 4×4 samples.
const BEST: (ShadingMode, Interpolation, u32) = (ShadingMode::Phong, PERSPECTIVE, 4);

/// A report scene; `benchmark` scenes make up the chart.
struct ReportScene {
    name: String,
    benchmark: bool,
    scene: Scene,
}

fn scenes(args: &Args) -> Result<Vec<ReportScene>> {
    let (w, h) = args.size;
    let sized = |mut s: Scene| {
        s.settings.width = w;
        s.settings.height = h;
        s
    };
    let mut out = Vec::new();
    match crate::bench::bunny(&args.assets) {
        Some(path) => {
            let model = zline::io::load_obj(&path).with_context(|| format!("loading {}", path.display()))?;
            let settings = RenderSettings { width: w, height: h, ..RenderSettings::default() };
            out.push(ReportScene {
                name: "bunny".into(),
                benchmark: true,
                scene: zline::io::scene_for_model(model, settings),
            });
        }
        None => eprintln!("note: the bunny is not under {}; skipped (pass --assets)", args.assets.display()),
    }
    out.push(ReportScene {
        name: "textured plane + fog".into(),
        benchmark: true,
        scene: sized(crate::bench::textured_plane(false)?),
    });
    out.push(ReportScene {
        name: "transparent spheres".into(),
        benchmark: true,
        scene: sized(crate::bench::textured_plane(true)?),
    });
    out.push(ReportScene {
        name: "sphere 1M".into(),
        benchmark: true,
        scene: sized(crate::bench::sphere_scene(500, 1000, 2.6, ShadingMode::Phong)),
    });
    for case in hard_cases() {
        out.push(ReportScene { name: format!("hard: {}", case.name), benchmark: false, scene: case.scene });
    }
    for s in &mut out {
        // The setting decides the shading of every object.
        for o in &mut s.scene.objects {
            o.shading = None;
        }
    }
    Ok(out)
}

/// One measured cell of the report.
struct Row {
    scene: usize,
    setting: usize,
    /// Fastest frame.
    ms: f64,
    median_ms: f64,
    best: ErrorStats,
    own: ErrorStats,
}

pub(crate) fn run(args: &Args) -> Result<()> {
    let settings = settings();
    let scenes: Vec<ReportScene> = scenes(args)?
        .into_iter()
        .filter(|s| args.filter.as_deref().is_none_or(|f| s.name.contains(f)))
        .collect();
    let shadow_chart = args.chart.with_file_name("report-shadows.png");
    if scenes.is_empty() && args.filter.as_deref() == Some("shadows") {
        let (markdown, points) = crate::report_shadows::section(args.frames)?;
        write(&args.out, markdown.as_bytes())?;
        crate::chart::draw(&shadow_chart, &args.font, &points, &crate::report_shadows::CHART)?;
        println!("wrote {} and {}", args.out.display(), shadow_chart.display());
        return Ok(());
    }
    let renderers_image = args.chart.with_file_name("report-renderers.png");
    if scenes.is_empty() && args.filter.as_deref() == Some("renderers") {
        let markdown = crate::report_renderers::section(&renderers_image)?;
        write(&args.out, markdown.as_bytes())?;
        println!("wrote {} and {}", args.out.display(), renderers_image.display());
        return Ok(());
    }
    if scenes.is_empty() && args.filter.as_deref() == Some("lod") {
        let markdown = crate::report_lod::section(&args.assets, args.frames)?;
        write(&args.out, markdown.as_bytes())?;
        println!("wrote {}", args.out.display());
        return Ok(());
    }
    if scenes.is_empty() && args.filter.as_deref() == Some("models") {
        let markdown = crate::report_models::section(&args.assets, args.frames)?;
        write(&args.out, markdown.as_bytes())?;
        println!("wrote {}", args.out.display());
        return Ok(());
    }
    if scenes.is_empty() {
        bail!("no scene matches the filter (\"shadows\", \"models\", \"lod\" or \"renderers\" gives that section alone)");
    }
    let mut rows = Vec::new();
    for (si, rs) in scenes.iter().enumerate() {
        let start = Instant::now();
        let mut truths: HashMap<(ShadingMode, Interpolation, u32), TruthImage> = HashMap::new();
        let mut truth = |key: (ShadingMode, Interpolation, u32)| -> TruthImage {
            truths
                .entry(key)
                .or_insert_with(|| {
                    let mut s = rs.scene.clone();
                    (s.settings.shading, s.settings.interpolation, s.settings.ssaa) = key;
                    render_truth(&s)
                })
                .clone()
        };
        let best = truth(BEST);
        let variants: Vec<Scene> = settings
            .iter()
            .map(|setting| {
                let mut scene = rs.scene.clone();
                setting.apply(&mut scene.settings);
                scene
            })
            .collect();
        let (times, images) = time_interleaved(&variants, args.frames);
        for (ki, setting) in settings.iter().enumerate() {
            let rgb = images[ki].to_rgb();
            let own = truth(setting.model());
            rows.push(Row {
                scene: si,
                setting: ki,
                ms: times[ki].0,
                median_ms: times[ki].1,
                best: ErrorStats::of_rgb8(&rgb, &best),
                own: ErrorStats::of_rgb8(&rgb, &own),
            });
        }
        eprintln!("{}: {:.1} s", rs.name, start.elapsed().as_secs_f64());
    }
    let points = chart_points(&scenes, &settings, &rows);
    let mut markdown = table(&scenes, &settings, &rows, &points, args);
    if args.filter.as_deref().is_none_or(|f| "shadows".contains(f)) {
        let start = Instant::now();
        let (section, shadow_points) = crate::report_shadows::section(args.frames)?;
        markdown += &section;
        crate::chart::draw(&shadow_chart, &args.font, &shadow_points, &crate::report_shadows::CHART)?;
        eprintln!("shadows: {:.1} s", start.elapsed().as_secs_f64());
    }
    if args.filter.as_deref().is_none_or(|f| "models".contains(f)) {
        let start = Instant::now();
        markdown += &crate::report_models::section(&args.assets, args.frames)?;
        eprintln!("lighting models: {:.1} s", start.elapsed().as_secs_f64());
    }
    if args.filter.is_none() {
        let start = Instant::now();
        markdown += &crate::report_lod::section(&args.assets, args.frames)?;
        eprintln!("simplified meshes: {:.1} s", start.elapsed().as_secs_f64());
        let start = Instant::now();
        markdown += &crate::report_renderers::section(&renderers_image)?;
        eprintln!("renderers: {:.1} s", start.elapsed().as_secs_f64());
    }
    write(&args.out, markdown.as_bytes())?;
    crate::chart::draw(&args.chart, &args.font, &points, &crate::chart::SETTINGS)?;
    for p in points.iter().filter(|p| p.name.contains("adaptive")) {
        println!("{}: {}", p.name, if p.pareto { "on the Pareto front" } else { "dominated" });
    }
    println!("wrote {} and {}", args.out.display(), args.chart.display());
    Ok(())
}

fn write(path: &Path, bytes: &[u8]) -> Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    }
    std::fs::write(path, bytes).with_context(|| format!("writing {}", path.display()))
}

fn table(
    scenes: &[ReportScene],
    settings: &[Setting],
    rows: &[Row],
    points: &[Point],
    args: &Args,
) -> String {
    let mut md = String::new();
    let threads = rayon::current_num_threads();
    let _ = writeln!(
        md,
        "# Speed against error\n\nMade by `cargo xtask report` ({}×{} for the benchmark scenes, each hard case at its own size; \
         fastest and median of {} frames taken in interleaved rounds, {threads} threads). Errors are in 8-bit steps against two f64 truths from `zline-truth`: \
         **best** = Phong, perspective-correct, 4×4 samples per pixel; **own** = the truth of the setting's own model \
         (same shading, interpolation and samples). *exact* is the share of pixels equal to the truth in all three channels; \
         *±1* pixels differ by one step in some channel (f32 against f64 arithmetic landing on either side of a \
         rounding boundary), *> 1* pixels lie on edges, where the fast renderer's 1/256-pixel vertex snap decides \
         coverage. The property tests of `crates/truth` hold the fast renderer to this on random scenes: more than 1 px \
         from every edge, each channel within ½ + 0.01 + the pixel's sensitivity to a 1/256-pixel move of 255·truth, \
         and at least 95 % of pixels exact.\n",
        args.size.0, args.size.1, args.frames
    );
    let _ = writeln!(
        md,
        "## Summary over the benchmark scenes\n\n\
         Time is the sum of the fastest frames; RMSE the mean; *worst exact vs own* the lowest share over the \
         benchmark scenes. *Pareto*: no other setting is both faster and more accurate.\n"
    );
    let _ = writeln!(md, "| # | setting | ms | mean RMSE vs best | worst exact vs own | Pareto |");
    let _ = writeln!(md, "|---:|---|---:|---:|---:|---|");
    for (k, p) in points.iter().enumerate() {
        let worst = rows
            .iter()
            .filter(|r| r.setting == k && scenes[r.scene].benchmark)
            .map(|r| r.own.share_exact)
            .fold(f64::INFINITY, f64::min);
        let _ = writeln!(
            md,
            "| {} | {} | {:.2} | {:.3} | {:.3} % | {} |",
            k + 1,
            p.name,
            p.ms,
            p.rmse,
            100.0 * worst,
            if p.pareto { "yes" } else { "" }
        );
    }
    md.push('\n');
    for (si, s) in scenes.iter().enumerate() {
        let _ = writeln!(md, "## {}\n", s.name);
        let _ = writeln!(
            md,
            "| setting | ms (fastest) | ms (median) | RMSE vs best | max vs best | > 1 vs best | exact vs own | ±1 vs own | > 1 vs own |"
        );
        let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
        for r in rows.iter().filter(|r| r.scene == si) {
            let _ = writeln!(
                md,
                "| {} | {:.2} | {:.2} | {:.3} | {:.0} | {:.3} % | {:.3} % | {:.3} % | {:.3} % |",
                settings[r.setting].name,
                r.ms,
                r.median_ms,
                r.best.rmse,
                r.best.max_abs,
                100.0 * r.best.share_over_1,
                100.0 * r.own.share_exact,
                100.0 * (1.0 - r.own.share_exact - r.own.share_over_1),
                100.0 * r.own.share_over_1
            );
        }
        md.push('\n');
    }
    md
}

fn chart_points(scenes: &[ReportScene], settings: &[Setting], rows: &[Row]) -> Vec<Point> {
    let n = scenes.iter().filter(|s| s.benchmark).count().max(1) as f64;
    let mut points: Vec<Point> = settings
        .iter()
        .enumerate()
        .map(|(ki, s)| {
            let bench = rows.iter().filter(|r| r.setting == ki && scenes[r.scene].benchmark);
            let (ms, rmse) = bench.fold((0.0, 0.0), |(t, e), r| (t + r.ms, e + r.best.rmse / n));
            Point { name: s.name.to_string(), ms, rmse, pareto: false }
        })
        .collect();
    for i in 0..points.len() {
        let dominated = points.iter().enumerate().any(|(j, q)| {
            j != i
                && q.ms <= points[i].ms
                && q.rmse <= points[i].rmse
                && (q.ms < points[i].ms || q.rmse < points[i].rmse)
        });
        points[i].pareto = !dominated;
    }
    points
}
