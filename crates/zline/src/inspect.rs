//! `zline inspect` and `render --inspect X,Y`: the pixel inspector's
//! report (`zline_pipeline::PixelTrace`) as text for a learner, or as JSON.

use serde::Serialize;
use zline_pipeline::{FragmentTrace, Outcome, Pass, PixelTrace};
use zline_scene::Scene;

fn rgb(c: glam::Vec3) -> String {
    format!("({:.6}, {:.6}, {:.6})", c.x, c.y, c.z)
}

fn depth(z: f32, far: f32) -> String {
    if z >= far {
        format!("{z:.6} (the far value: nothing drawn)")
    } else {
        format!("{z:.6}")
    }
}

fn pass_name(p: Pass) -> &'static str {
    match p {
        Pass::Opaque => "opaque",
        Pass::Transparent => "transparent",
        Pass::Painter => "painter",
    }
}

fn outcome_name(o: Outcome) -> &'static str {
    match o {
        Outcome::Written => "written",
        Outcome::Hidden => "hidden",
        Outcome::Discarded => "discarded",
        Outcome::Blended => "blended",
    }
}

fn object_name(scene: &Scene, object: u32) -> String {
    scene.objects.get(object as usize).map_or_else(String::new, |o| format!(" {:?}", o.mesh.name))
}

fn fragment_text(out: &mut String, k: usize, f: &FragmentTrace, scene: &Scene, far: f32) {
    use std::fmt::Write;
    let triangle = f.triangle.map_or_else(String::new, |t| format!(" triangle {t}"));
    let _ = writeln!(
        out,
        "  fragment {k}: {} pass, object {}{}{triangle}, kernel {:?}",
        pass_name(f.pass),
        f.object,
        object_name(scene, f.object),
        f.kernel
    );
    let [a, b, c] = f.vertices;
    let _ = writeln!(
        out,
        "    window vertices (snapped to 1/256): ({:.4}, {:.4}) ({:.4}, {:.4}) ({:.4}, {:.4})",
        a.0, a.1, b.0, b.1, c.0, c.1
    );
    let edge = if f.on_edge {
        "exactly on an edge: in by the top-left rule (a left or top edge)"
    } else {
        "strictly inside"
    };
    let _ = writeln!(
        out,
        "    edge table: sample row {} spans columns {}..{} (half-open: left edges in, right edges out); the sample is {edge}",
        f.span.y, f.span.x0, f.span.x1
    );
    let test = match (f.pass, f.outcome) {
        (Pass::Painter, _) => "no depth test (the painter's algorithm)".to_string(),
        (_, Outcome::Hidden) => format!("z {:.6} >= stored {}: failed, hidden", f.z, depth(f.before.0, far)),
        (_, outcome) => {
            format!("z {:.6} < stored {}: passed, {}", f.z, depth(f.before.0, far), outcome_name(outcome))
        }
    };
    let _ = writeln!(
        out,
        "    depth: z = {:.6} (NC depth, stepped along the span by dz/dx = {:.4e}); {test}",
        f.z, f.dzdx
    );
    let _ = writeln!(out, "    colour: {} -> {}", rgb(f.before.1), rgb(f.after.1));
}

/// The report as text: per sample, each fragment in the order drawn, then
/// the resolve and the check against the rendered pixel.
pub fn text(trace: &PixelTrace, scene: &Scene) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    let (x, y) = trace.pixel;
    let n = trace.n;
    let _ = writeln!(
        out,
        "pixel ({x}, {y}) of {}x{}: {} sample{} ({n}x{n}); {} object{}",
        scene.settings.width,
        scene.settings.height,
        n * n,
        if n == 1 { "" } else { "s" },
        scene.objects.len(),
        if scene.objects.len() == 1 { "" } else { "s" }
    );
    if let Some(note) = &trace.note {
        let _ = writeln!(out, "note: {note}");
    }
    for (i, s) in trace.samples.iter().enumerate() {
        let _ = writeln!(out, "sample {} at ({:.4}, {:.4}):", i + 1, s.position.0, s.position.1);
        if s.fragments.is_empty() {
            let _ = writeln!(out, "  no triangle covers it");
        }
        let opaque = s.fragments.iter().take_while(|f| f.pass != Pass::Transparent).count();
        for (k, f) in s.fragments[..opaque].iter().enumerate() {
            fragment_text(&mut out, k + 1, f, scene, trace.far);
        }
        let _ = writeln!(
            out,
            "  after the {} pass: depth {}, colour {}",
            if s.fragments.iter().any(|f| f.pass == Pass::Painter) { "painter's" } else { "opaque" },
            depth(s.after_opaque.0, trace.far),
            rgb(s.after_opaque.1)
        );
        if let Some(c) = s.after_fog {
            let _ = writeln!(out, "  after fog: colour {}", rgb(c));
        }
        for (k, f) in s.fragments[opaque..].iter().enumerate() {
            fragment_text(&mut out, opaque + k + 1, f, scene, trace.far);
        }
        let _ = writeln!(out, "  the resolve reads colour {}, alpha {:.6}", rgb(s.last.1), s.last.2);
    }
    let [r, g, b, a] = trace.resolved;
    let tone = trace.tone;
    let _ = writeln!(
        out,
        "resolve: the mean of the {} sample{}, tone mapping {} (exposure {}), then floor(c·255 + ½) per channel: {r} {g} {b} (alpha {a})",
        n * n,
        if n == 1 { "" } else { "s" },
        tone.operator.name(),
        tone.exposure
    );
    let [ir, ig, ib, ia] = trace.image;
    if trace.matches() {
        let _ = writeln!(out, "the rendered image's pixel is the same: {ir} {ig} {ib} (alpha {ia})");
    } else {
        let _ = writeln!(out, "MISMATCH: the rendered image's pixel is {ir} {ig} {ib} (alpha {ia})");
    }
    out
}

#[derive(Serialize)]
struct FragmentJson {
    pass: &'static str,
    object: u32,
    object_name: Option<String>,
    triangle: Option<u32>,
    kernel: String,
    window_vertices: [[f64; 2]; 3],
    span: [i32; 3],
    on_edge: bool,
    z: f32,
    dzdx: f64,
    depth_before: f32,
    depth_after: f32,
    color_before: [f32; 3],
    color_after: [f32; 3],
    outcome: &'static str,
}

#[derive(Serialize)]
struct SampleJson {
    position: [f64; 2],
    fragments: Vec<FragmentJson>,
    after_opaque: (f32, [f32; 3]),
    after_fog: Option<[f32; 3]>,
    resolve_reads: (f32, [f32; 3], f32),
}

#[derive(Serialize)]
struct TraceJson {
    pixel: [u32; 2],
    size: [u32; 2],
    samples_per_side: u32,
    far: f32,
    note: Option<String>,
    samples: Vec<SampleJson>,
    resolved: [u8; 4],
    image: [u8; 4],
    matches: bool,
}

/// The report as JSON (one object; colours linear RGB before the resolve,
/// bytes RGBA after it).
pub fn json(trace: &PixelTrace, scene: &Scene) -> String {
    let samples = trace
        .samples
        .iter()
        .map(|s| SampleJson {
            position: [s.position.0, s.position.1],
            fragments: s
                .fragments
                .iter()
                .map(|f| FragmentJson {
                    pass: pass_name(f.pass),
                    object: f.object,
                    object_name: scene.objects.get(f.object as usize).map(|o| o.mesh.name.clone()),
                    triangle: f.triangle,
                    kernel: format!("{:?}", f.kernel),
                    window_vertices: f.vertices.map(|(x, y)| [x, y]),
                    span: [f.span.y, f.span.x0, f.span.x1],
                    on_edge: f.on_edge,
                    z: f.z,
                    dzdx: f.dzdx,
                    depth_before: f.before.0,
                    depth_after: f.after.0,
                    color_before: f.before.1.to_array(),
                    color_after: f.after.1.to_array(),
                    outcome: outcome_name(f.outcome),
                })
                .collect(),
            after_opaque: (s.after_opaque.0, s.after_opaque.1.to_array()),
            after_fog: s.after_fog.map(|c| c.to_array()),
            resolve_reads: (s.last.0, s.last.1.to_array(), s.last.2),
        })
        .collect();
    let report = TraceJson {
        pixel: [trace.pixel.0, trace.pixel.1],
        size: [scene.settings.width, scene.settings.height],
        samples_per_side: trace.n,
        far: trace.far,
        note: trace.note.clone(),
        samples,
        resolved: trace.resolved,
        image: trace.image,
        matches: trace.matches(),
    };
    serde_json::to_string_pretty(&report).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}
