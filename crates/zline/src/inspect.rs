//! `zline inspect` and `render --inspect X,Y`: the pixel inspector's
//! report (`zline_pipeline::PixelTrace`) as text for a learner, or as JSON.

use glam::Vec3;
use serde::Serialize;
use zline_pipeline::{FragmentTrace, Outcome, Pass, PixelTrace, SampleAttributes};
use zline_scene::Scene;
use zline_shading::{Light, LightingModel};

/// One light's share at a sample: SPEC §5's terms with that light alone.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightTerm {
    /// The light's index in the scene.
    pub light: usize,
    /// Its kind: point, spot or directional.
    pub kind: &'static str,
    /// f_att (1 for a directional light), times the spot's falloff.
    pub attenuation: f32,
    /// N·L (before the max with 0).
    pub n_dot_l: f32,
    /// The share of the light the sample sees: 1 lit, 0 in shadow (the
    /// shadow maps' lookup or the planar mask), between with filtering.
    pub share: f32,
    /// f·Il·kd·max(0, N·L).
    pub diffuse: [f32; 3],
    /// f·Il·ks·max(0, N·H)^ns (Cook–Torrance: its specular lobe).
    pub specular: [f32; 3],
}

/// SPEC §5 at a sample of object `object`: the ambient term ka·Ia (plus
/// the emission ke) and each light's terms, from the interpolated eye-space
/// position and the renormalized normal, with the object's material (a
/// texel or vertex colour, which multiplies ka and kd, is not applied),
/// each light's terms times the share `shares` says the sample sees (1
/// where it says nothing). `None` where the kernel interpolates no normal
/// (flat and Gouraud shading lit at the centroid or the vertices).
pub fn lighting_terms(
    scene: &Scene,
    object: u32,
    a: &SampleAttributes,
    shares: &[f32],
) -> Option<(Vec3, Vec<LightTerm>)> {
    let (normal, point) = (a.normal?.normalize_or_zero(), a.eye?);
    let material = scene.objects.get(object as usize)?.material().sanitized();
    let view = scene.camera.eye_from_world();
    let eye = if scene.camera.projection.is_perspective() { Vec3::ZERO } else { point + Vec3::Z };
    let alone = |ambient: Vec3, lights: Vec<Light>| {
        LightingModel { ambient, lights, environment: None }.shade_parts(&material, point, normal, eye)
    };
    let ambient = alone(scene.ambient, vec![]);
    let base = ambient.ambient_diffuse + ambient.specular;
    let terms = scene
        .lights
        .iter()
        .enumerate()
        .map(|(k, light)| {
            let l = light.transformed(&view);
            let parts = alone(Vec3::ZERO, vec![l]);
            let (kind, to_light, attenuation) = match l {
                Light::Point { position, attenuation, .. } => {
                    ("point", position - point, attenuation.factor(position.distance(point)))
                }
                Light::Spot { position, direction, attenuation, cone, .. } => {
                    let to = position - point;
                    let cos = (-to.normalize_or_zero()).dot(direction.normalize_or_zero());
                    ("spot", to, attenuation.factor(to.length()) * cone.factor(cos))
                }
                Light::Directional { direction, .. } => ("directional", -direction, 1.0),
            };
            let share = shares.get(k).copied().unwrap_or(1.0);
            LightTerm {
                light: k,
                kind,
                attenuation,
                n_dot_l: normal.dot(to_light.normalize_or_zero()),
                share,
                diffuse: (parts.ambient_diffuse * share).to_array(),
                specular: ((parts.specular - material.ke) * share).to_array(),
            }
        })
        .collect();
    Some((base, terms))
}

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
    attributes_text(out, f, scene);
    let _ = writeln!(out, "    colour: {} -> {}", rgb(f.before.1), rgb(f.after.1));
}

/// The triangle's vertices in each space of SPEC §1, with the frame's
/// matrices in f32 (the window position in the trace is the one setup
/// snapped, exactly): object, world, eye, clip, NC.
pub fn vertex_spaces(scene: &Scene, object: u32, triangle: u32) -> Option<[[glam::Vec4; 3]; 5]> {
    let o = scene.objects.get(object as usize)?;
    let t = o.mesh.triangles.get(triangle as usize)?;
    let aspect = scene.settings.width.max(1) as f32 / scene.settings.height.max(1) as f32;
    let view = scene.camera.eye_from_world();
    let projection = scene.camera.clip_from_eye(aspect);
    let p = t.map(|i| o.mesh.positions.get(i as usize).copied().unwrap_or(Vec3::NAN).extend(1.0));
    let world = p.map(|v| o.world_from_object * v);
    let eye = world.map(|v| view * v);
    let clip = eye.map(|v| projection * v);
    let nc = clip.map(|v| v / v.w);
    Some([p, world, eye, clip, nc])
}

fn attributes_text(out: &mut String, f: &FragmentTrace, scene: &Scene) {
    use std::fmt::Write;
    let a = &f.attributes;
    if let Some(spaces) = f.triangle.and_then(|t| vertex_spaces(scene, f.object, t)) {
        let names = ["object", "world", "eye", "clip", "NC"];
        for (name, vs) in names.iter().zip(spaces) {
            let v = vs.map(|v| {
                if *name == "clip" {
                    format!("({:.4}, {:.4}, {:.4}, {:.4})", v.x, v.y, v.z, v.w)
                } else {
                    format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z)
                }
            });
            let _ = writeln!(out, "    {name} vertices: {} {} {}", v[0], v[1], v[2]);
        }
    }
    let mut parts = Vec::new();
    if let Some(n) = a.normal {
        parts.push(format!(
            "normal {} (|n| {:.4} before renormalizing)",
            rgb(n.normalize_or_zero()),
            n.length()
        ));
    }
    if let Some(p) = a.eye {
        parts.push(format!("eye-space position {}", rgb(p)));
    }
    if let Some(uv) = a.uv {
        parts.push(format!("texture coordinates ({:.6}, {:.6})", uv.x, uv.y));
    }
    if let Some(c) = a.vertex_color {
        parts.push(format!("vertex colour {}", rgb(c)));
    }
    if let Some(c) = a.gouraud {
        parts.push(format!("Gouraud colour {} (lit at the vertices, interpolated)", rgb(c)));
    }
    if let Some((ad, s)) = a.lit_parts {
        parts.push(format!("lit once: ambient+diffuse {} (times the texel), specular {}", rgb(ad), rgb(s)));
    }
    if let Some(c) = a.flat {
        parts.push(format!("flat colour {} (lit once at the centroid)", rgb(c)));
    }
    if let Some(r) = a.texture {
        parts.push(format!(
            "texture {}x{} ({} mip levels, {:?}): level of detail {:.4}, texel read {}, alpha {:.6}",
            r.size.0,
            r.size.1,
            r.levels,
            r.filter,
            r.lod,
            rgb(r.texel.truncate()),
            r.texel.w
        ));
    }
    for p in parts {
        let _ = writeln!(out, "    {p}");
    }
    if let Some((base, terms)) = lighting_terms(scene, f.object, a, &f.light_shares) {
        let _ = writeln!(out, "    lighting (SPEC §5, before the texel): ke + ka·Ia = {}", rgb(base));
        for t in terms {
            let _ = writeln!(
                out,
                "      light {} ({}): N·L {:.4}, attenuation {:.4}, seen {:.4}, diffuse {}, specular {}",
                t.light,
                t.kind,
                t.n_dot_l,
                t.attenuation,
                t.share,
                rgb(Vec3::from(t.diffuse)),
                rgb(Vec3::from(t.specular))
            );
        }
    }
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
    normal: Option<[f32; 3]>,
    eye_position: Option<[f32; 3]>,
    texture_coordinates: Option<[f32; 2]>,
    vertex_color: Option<[f32; 3]>,
    gouraud_color: Option<[f32; 3]>,
    texture_lod: Option<f32>,
    texel: Option<[f32; 4]>,
    /// The triangle's vertices in object, world, eye, clip and NC space.
    vertex_spaces: Option<[[[f32; 4]; 3]; 5]>,
    ambient: Option<[f32; 3]>,
    lights: Option<Vec<LightTerm>>,
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
                .map(|f| (f, lighting_terms(scene, f.object, &f.attributes, &f.light_shares)))
                .map(|(f, lighting)| FragmentJson {
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
                    normal: f.attributes.normal.map(|n| n.normalize_or_zero().to_array()),
                    eye_position: f.attributes.eye.map(|v| v.to_array()),
                    texture_coordinates: f.attributes.uv.map(|v| v.to_array()),
                    vertex_color: f.attributes.vertex_color.map(|v| v.to_array()),
                    gouraud_color: f.attributes.gouraud.map(|v| v.to_array()),
                    texture_lod: f.attributes.texture.map(|r| r.lod),
                    texel: f.attributes.texture.map(|r| r.texel.to_array()),
                    vertex_spaces: f
                        .triangle
                        .and_then(|t| vertex_spaces(scene, f.object, t))
                        .map(|s| s.map(|vs| vs.map(|v| v.to_array()))),
                    ambient: lighting.as_ref().map(|(b, _)| b.to_array()),
                    lights: lighting.map(|(_, t)| t),
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
