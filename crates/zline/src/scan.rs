//! Scan conversion step by step (`zline scan`): the edge table and the
//! active edge list of one triangle in window space, row by row, with the
//! spans it covers and the depth along each, for the classroom.
//!
//! The spans are `zline-raster`'s own ([`EdgeTable::scan`], the fixed-point
//! walk and top-left rule the renderer draws with), over the vertices
//! snapped to its 1/256-pixel grid. The edge table beside them is the
//! textbook's description of the same walk, in pixels: per edge the first
//! row whose centre it reaches (y_min), x where it crosses that row's
//! centre, 1/m = Δx/Δy (what x gains from one row to the next) and the row
//! it stops before (y_max). Horizontal edges cover no row and are left
//! out. The depth along a span is the plane through the vertices' depths,
//! z(x + 1) = z(x) + ∂z/∂x (the course's z(x+1) = z(x) − A/C).

use serde::Serialize;
use zline_raster::{first_sample_at_or_after, DepthPlane, EdgeTable, FixedPoint, PlaneBasis, Rect};

/// One edge of the edge table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EdgeEntry {
    /// Which edge: `long` (top to bottom vertex), `upper` or `lower`.
    pub name: &'static str,
    /// Its end points in pixels, upper first.
    pub from: (f64, f64),
    /// Its lower end point.
    pub to: (f64, f64),
    /// The first row whose centre it reaches.
    pub y_min: i64,
    /// The row it stops before.
    pub y_max: i64,
    /// x where it crosses row `y_min`'s centre.
    pub x_at_y_min: f64,
    /// Δx / Δy: x's step from one row to the next.
    pub inverse_slope: f64,
}

/// One row of the walk.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RowTrace {
    /// The row.
    pub y: i64,
    /// The active edges, left then right, with x at the row's centre.
    pub active: [(&'static str, f64); 2],
    /// The covered columns `x0..x1` (half-open), when any.
    pub span: Option<(i64, i64)>,
    /// The depth at each covered sample, stepped by ∂z/∂x from the first.
    pub depth: Vec<f64>,
}

/// The trace of one triangle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScanTrace {
    /// The vertices as snapped (pixels), sorted top to bottom.
    pub vertices: [(f64, f64); 3],
    /// The edge table, sorted by `y_min`.
    pub edges: Vec<EdgeEntry>,
    /// ∂z/∂x of the depth plane.
    pub dzdx: f64,
    /// Every row from the top edge's first row to the bottom's last.
    pub rows: Vec<RowTrace>,
}

/// The trace of the triangle `vertices` (x, y in pixels, y down; z the
/// depth) inside an image of `width` × `height` pixels; `Err` says why
/// there is none (off the grid, zero area, too many rows to print).
pub fn trace(vertices: [[f32; 3]; 3], width: u32, height: u32) -> Result<ScanTrace, String> {
    let snapped = vertices
        .iter()
        .map(|v| FixedPoint::snap(v[0], v[1]).ok_or_else(|| format!("vertex {v:?} is off the window grid")))
        .collect::<Result<Vec<_>, _>>()?;
    let p = [snapped[0], snapped[1], snapped[2]];
    let table = EdgeTable::new(p).ok_or("the triangle has zero area (its snapped vertices are collinear)")?;
    let bounds = table.bounds().intersect(&Rect::from_size(0, 0, width as i32, height as i32));
    if bounds.height() > 4096 {
        return Err(format!("{} rows: at most 4096 are traced", bounds.height()));
    }
    let [top, mid, bottom] = table.sorted_vertices();
    let px = |q: FixedPoint| q.to_f64();
    let edge = |name, a: FixedPoint, b: FixedPoint| -> Option<EdgeEntry> {
        let (y_min, y_max) = (first_sample_at_or_after(a.y.into()), first_sample_at_or_after(b.y.into()));
        let ((ax, ay), (bx, by)) = (px(a), px(b));
        (by > ay).then(|| {
            let inverse_slope = (bx - ax) / (by - ay);
            EdgeEntry {
                name,
                from: (ax, ay),
                to: (bx, by),
                y_min,
                y_max,
                x_at_y_min: ax + (y_min as f64 + 0.5 - ay) * inverse_slope,
                inverse_slope,
            }
        })
    };
    let mut edges: Vec<EdgeEntry> =
        [edge("long", top, bottom), edge("upper", top, mid), edge("lower", mid, bottom)]
            .into_iter()
            .flatten()
            .collect();
    edges.sort_by_key(|e| (e.y_min, e.name != "long"));
    // The renderer's spans, by row.
    let mut spans = std::collections::BTreeMap::new();
    table.scan(Rect::from_size(0, 0, width as i32, height as i32), |s| {
        spans.insert(i64::from(s.y), (i64::from(s.x0), i64::from(s.x1)));
    });
    // The depth plane, in the order the vertices were given.
    let basis = PlaneBasis::new(p).ok_or("the triangle has zero area")?;
    let plane = DepthPlane::new(&basis, vertices.map(|v| f64::from(v[2])));
    let dzdx = plane.dzdx();
    let x_at = |e: &EdgeEntry, y: i64| e.x_at_y_min + (y - e.y_min) as f64 * e.inverse_slope;
    let long = edges.iter().find(|e| e.name == "long").cloned();
    let mid_row = first_sample_at_or_after(mid.y.into());
    let mut rows = Vec::new();
    for y in i64::from(bounds.y0)..i64::from(bounds.y1) {
        let Some(long) = &long else { break };
        let short_name = if y < mid_row { "upper" } else { "lower" };
        let Some(short) = edges.iter().find(|e| e.name == short_name) else { continue };
        let (l, r) = ((long.name, x_at(long, y)), (short.name, x_at(short, y)));
        let active = if table.long_edge_is_left() { [l, r] } else { [r, l] };
        let span = spans.get(&y).copied();
        let depth = span.map_or_else(Vec::new, |(x0, x1)| {
            let first = plane.at(x0 as f64 + 0.5, y as f64 + 0.5);
            (0..x1 - x0).map(|k| first + k as f64 * dzdx).collect()
        });
        rows.push(RowTrace { y, active, span, depth });
    }
    Ok(ScanTrace { vertices: [px(top), px(mid), px(bottom)], edges, dzdx, rows })
}

/// Triangle `index` of object `object` of `scene`, taken to window space
/// by the renderer's own mapping (`zline_pipeline::vertex::Projected`:
/// the scene's camera, the divide by w, the viewport of its settings):
/// three vertices (x, y, NC depth). `Err` says why there is none: no such
/// triangle, or one the near or far plane clips (the trace shows
/// triangles whole; the clipper would cut it into others).
pub fn window_triangle(
    scene: &zline_scene::Scene,
    object: usize,
    index: usize,
) -> Result<[[f32; 3]; 3], String> {
    use zline_pipeline::vertex::{Projected, Viewport};
    let o = scene
        .objects
        .get(object)
        .ok_or_else(|| format!("no object {object} (the scene has {})", scene.objects.len()))?;
    let tri = o.mesh.triangles.get(index).ok_or_else(|| {
        format!("object {object} has no triangle {index} ({} triangles)", o.mesh.triangles.len())
    })?;
    let (w, h) = (scene.settings.width, scene.settings.height);
    let aspect = w.max(1) as f32 / h.max(1) as f32;
    let clip_from_object =
        scene.camera.clip_from_eye(aspect) * scene.camera.eye_from_world() * o.world_from_object;
    let viewport = Viewport { width: w, height: h };
    let mut out = [[0.0f32; 3]; 3];
    for (k, &i) in tri.iter().enumerate() {
        let clip = clip_from_object * o.mesh.positions[i as usize].extend(1.0);
        let inside = clip.w > 0.0 && clip.z >= -clip.w && clip.z <= clip.w;
        let projected = Projected::new(clip, viewport).filter(|_| inside).ok_or_else(|| {
            format!("triangle {index} of object {object} crosses the near or far plane: the clipper cuts it, pick another")
        })?;
        let (x, y) = projected.fixed.to_f64();
        out[k] = [x as f32, y as f32, projected.z as f32];
    }
    Ok(out)
}

impl ScanTrace {
    /// The trace as the text `zline scan` prints.
    pub fn text(&self) -> String {
        use std::fmt::Write as _;
        let mut out = String::new();
        let v = self.vertices;
        let _ = writeln!(
            out,
            "vertices (snapped to 1/256 pixel, top to bottom): {:?} {:?} {:?}",
            v[0], v[1], v[2]
        );
        let _ = writeln!(out, "\nedge table (sorted by y_min; horizontal edges left out):");
        let _ = writeln!(out, "  edge    y_min  y_max  x at y_min      1/m");
        for e in &self.edges {
            let _ = writeln!(
                out,
                "  {:<6} {:>6} {:>6} {:>11.4} {:>8.4}",
                e.name, e.y_min, e.y_max, e.x_at_y_min, e.inverse_slope
            );
        }
        let _ = writeln!(out, "\nscan lines (active edge list at the row's centre; span x0..x1, half-open):");
        let _ = writeln!(out, "depth along a span: z(x+1) = z(x) + dz/dx, dz/dx = {:.6}", self.dzdx);
        for r in &self.rows {
            let [(ln, lx), (rn, rx)] = r.active;
            let span = match r.span {
                Some((x0, x1)) => format!("span {x0}..{x1}"),
                None => "no sample".into(),
            };
            let depth = match (r.depth.first(), r.depth.last()) {
                (Some(a), Some(b)) => format!("  z {a:.6} .. {b:.6}"),
                _ => String::new(),
            };
            let _ = writeln!(out, "  y {:>4}: AEL [{ln} {lx:.4}, {rn} {rx:.4}]  {span}{depth}", r.y);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_right_triangle_traces_as_by_hand() {
        // Legs on x = 0 and y = 0, hypotenuse x + y = 4; depth z = x / 4.
        let t = trace([[0.0, 0.0, 0.0], [0.0, 4.0, 0.0], [4.0, 0.0, 1.0]], 8, 8).unwrap();
        // Sorted by (y, x): top (0, 0), middle (4, 0), bottom (0, 4). The
        // upper edge (0,0)–(4,0) is horizontal: left out.
        assert_eq!(t.vertices, [(0.0, 0.0), (4.0, 0.0), (0.0, 4.0)]);
        let names: Vec<&str> = t.edges.iter().map(|e| e.name).collect();
        assert_eq!(names, ["long", "lower"]);
        let (long, lower) = (&t.edges[0], &t.edges[1]);
        assert_eq!((long.y_min, long.y_max, long.x_at_y_min, long.inverse_slope), (0, 4, 0.0, 0.0));
        assert_eq!((lower.y_min, lower.y_max, lower.x_at_y_min, lower.inverse_slope), (0, 4, 3.5, -1.0));
        // Row y covers the centres x + 0.5 < 3.5 − y: columns 0..3−y.
        let spans: Vec<Option<(i64, i64)>> = t.rows.iter().map(|r| r.span).collect();
        assert_eq!(spans, [Some((0, 3)), Some((0, 2)), Some((0, 1)), None]);
        assert_eq!(t.rows[1].active, [("long", 0.0), ("lower", 2.5)]);
        // z = x/4 at the centres 0.5, 1.5, 2.5; ∂z/∂x = 1/4.
        assert_eq!(t.dzdx, 0.25);
        assert_eq!(t.rows[0].depth, [0.125, 0.375, 0.625]);
        assert!(t.text().contains("lower       0      4      3.5000  -1.0000"), "{}", t.text());
        assert!(trace([[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0]], 8, 8)
            .unwrap_err()
            .contains("zero area"));
    }

    #[test]
    fn the_renderers_spans_are_the_active_edges_rule() {
        // Row y covers the columns whose centre c satisfies left ≤ c < right
        // at the row's centre: x0 = ⌈left − ½⌉, x1 = ⌈right − ½⌉.
        let mut seed = 12345u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1 << 24) as f32 * 40.0 - 4.0
        };
        let mut rows = 0;
        for _ in 0..200 {
            let v = [[next(), next(), 0.0], [next(), next(), 0.5], [next(), next(), 1.0]];
            let Ok(t) = trace(v, 32, 32) else { continue };
            for r in &t.rows {
                let [(_, l), (_, rt)] = r.active;
                let (x0, x1) = ((l - 0.5).ceil().max(0.0) as i64, (rt - 0.5).ceil().min(32.0) as i64);
                // Centres exactly on an edge are decided in fixed point; the
                // f64 crossing may land a hair either side.
                let ties = [l, rt].iter().any(|x| ((x - 0.5) - (x - 0.5).round()).abs() < 1e-9);
                if !ties {
                    assert_eq!(r.span, (x0 < x1).then_some((x0, x1)), "row {} of {v:?}", r.y);
                    rows += 1;
                }
            }
        }
        assert!(rows > 1000, "{rows} rows checked");
    }
}
