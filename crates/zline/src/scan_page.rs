//! The scan trace drawn ([`picture`]: the pixel grid magnified, the
//! covered samples filled, the edges over them) and as a self-contained
//! HTML page that steps through it row by row, forward and back
//! ([`page`]), for the classroom.

use zline_pipeline::Image;

use crate::scan::ScanTrace;

/// Pixels of the picture per window pixel.
pub const CELL: u32 = 16;

/// The rows and columns the picture shows: the trace's bounding box of
/// rows and spans, one pixel of margin.
fn frame(trace: &ScanTrace) -> (i64, i64, i64, i64) {
    let xs = trace.vertices.iter().map(|v| v.0);
    let (x_lo, x_hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    let ys = trace.vertices.iter().map(|v| v.1);
    let (y_lo, y_hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| (a.min(y), b.max(y)));
    (x_lo.floor() as i64 - 1, y_lo.floor() as i64 - 1, x_hi.ceil() as i64 + 1, y_hi.ceil() as i64 + 1)
}

/// The picture of the first `rows` rows of the trace (all of them for
/// `usize::MAX`): grid lines, sample centres, the covered samples of the
/// rows done in green, the current row's in yellow, the edges in red.
/// `None` when it would be larger than 4096 pixels a side.
pub fn picture(trace: &ScanTrace, rows: usize) -> Option<Image> {
    let (x0, y0, x1, y1) = frame(trace);
    let (w, h) = (u32::try_from(x1 - x0).ok()? * CELL, u32::try_from(y1 - y0).ok()? * CELL);
    if w > 4096 || h > 4096 {
        return None;
    }
    let rgba = |r: u8, g: u8, b: u8| u32::from_le_bytes([r, g, b, 255]);
    let mut image = Image {
        width: w,
        height: h,
        pixels: vec![rgba(250, 250, 250); (w * h) as usize],
        transparent: false,
    };
    let fill = |px: i64, py: i64, colour: u32, image: &mut Image| {
        let (cx, cy) = ((px - x0) as u32 * CELL, (py - y0) as u32 * CELL);
        for y in cy..cy + CELL {
            for x in cx..cx + CELL {
                image.pixels[(y * w + x) as usize] = colour;
            }
        }
    };
    let shown = rows.min(trace.rows.len());
    for (k, r) in trace.rows.iter().take(shown).enumerate() {
        let colour = if k + 1 == shown { rgba(250, 210, 60) } else { rgba(120, 200, 120) };
        if let Some((a, b)) = r.span {
            for x in a..b {
                fill(x, r.y, colour, &mut image);
            }
        }
    }
    // Grid lines and sample centres.
    for y in 0..h {
        for x in 0..w {
            if x % CELL == 0 || y % CELL == 0 {
                image.pixels[(y * w + x) as usize] = rgba(200, 200, 200);
            }
            if x % CELL == CELL / 2 && y % CELL == CELL / 2 {
                image.pixels[(y * w + x) as usize] = rgba(40, 40, 40);
            }
        }
    }
    // The edges, stepped finely along their length.
    let v = trace.vertices;
    for (a, b) in [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])] {
        let length = ((b.0 - a.0).hypot(b.1 - a.1) * f64::from(CELL) * 2.0).ceil().max(1.0) as usize;
        for i in 0..=length {
            let t = i as f64 / length as f64;
            let (x, y) = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
            let (px, py) =
                (((x - x0 as f64) * f64::from(CELL)) as i64, ((y - y0 as f64) * f64::from(CELL)) as i64);
            if (0..i64::from(w)).contains(&px) && (0..i64::from(h)).contains(&py) {
                image.pixels[(py as u32 * w + px as u32) as usize] = rgba(220, 30, 30);
            }
        }
    }
    Some(image)
}

/// A self-contained HTML page stepping through `trace` (its JSON inside):
/// the edge table, then a canvas of the grid, the edges and the spans
/// filled so far, with the row's active edge list and span beside it.
/// ←/→ or the buttons step; `#step=N` in the address opens step N.
pub fn page(trace: &ScanTrace) -> String {
    let json = serde_json::to_string(trace).unwrap_or_else(|_| "null".into()).replace("</", "<\\/");
    PAGE.replace("__TRACE__", &json).replace("__CELL__", &CELL.to_string())
}

const PAGE: &str = r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>zline scan: scan conversion step by step</title>
<style>body{font:14px sans-serif;margin:1em}table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}
#row{font-family:monospace;margin:.5em 0}canvas{border:1px solid #999}</style></head>
<body><h1>Scan conversion step by step</h1>
<p>The edge table, then one scan line a step: the active edge list at the row's centre, the span the renderer covers (top-left rule: left ≤ centre &lt; right) and the depth along it.</p>
<table id="edges"><tr><th>edge</th><th>y_min</th><th>y_max</th><th>x at y_min</th><th>1/m</th></tr></table>
<p><button id="back">← back</button> <button id="next">next →</button> <span id="step"></span></p>
<div id="row"></div><canvas id="grid"></canvas>
<script>
const T = __TRACE__, C = __CELL__;
const xs = T.vertices.map(v => v[0]), ys = T.vertices.map(v => v[1]);
const X0 = Math.floor(Math.min(...xs)) - 1, Y0 = Math.floor(Math.min(...ys)) - 1;
const X1 = Math.ceil(Math.max(...xs)) + 1, Y1 = Math.ceil(Math.max(...ys)) + 1;
const canvas = document.getElementById('grid');
canvas.width = (X1 - X0) * C; canvas.height = (Y1 - Y0) * C;
const g = canvas.getContext('2d');
for (const e of T.edges) {
  const tr = document.getElementById('edges').insertRow();
  for (const v of [e.name, e.y_min, e.y_max, e.x_at_y_min.toFixed(4), e.inverse_slope.toFixed(4)]) tr.insertCell().textContent = v;
}
let step = Math.max(0, Math.min(T.rows.length, parseInt((location.hash.match(/step=(\d+)/) || [0, 0])[1])));
function draw() {
  g.fillStyle = '#fafafa'; g.fillRect(0, 0, canvas.width, canvas.height);
  T.rows.slice(0, step).forEach((r, k) => {
    if (!r.span) return;
    g.fillStyle = k + 1 === step ? '#fad23c' : '#78c878';
    g.fillRect((r.span[0] - X0) * C, (r.y - Y0) * C, (r.span[1] - r.span[0]) * C, C);
  });
  g.strokeStyle = '#ccc';
  for (let x = 0; x <= X1 - X0; x++) { g.beginPath(); g.moveTo(x * C, 0); g.lineTo(x * C, canvas.height); g.stroke(); }
  for (let y = 0; y <= Y1 - Y0; y++) { g.beginPath(); g.moveTo(0, y * C); g.lineTo(canvas.width, y * C); g.stroke(); }
  g.fillStyle = '#282828';
  for (let y = 0; y < Y1 - Y0; y++) for (let x = 0; x < X1 - X0; x++) g.fillRect(x * C + C / 2 - 1, y * C + C / 2 - 1, 2, 2);
  g.strokeStyle = '#dc1e1e'; g.beginPath();
  T.vertices.forEach((v, i) => { const p = [(v[0] - X0) * C, (v[1] - Y0) * C]; i ? g.lineTo(...p) : g.moveTo(...p); });
  g.closePath(); g.stroke();
  const r = T.rows[step - 1];
  document.getElementById('step').textContent = 'step ' + step + ' of ' + T.rows.length;
  document.getElementById('row').textContent = !r ? 'the edge table, before the first scan line' :
    'y ' + r.y + ': AEL [' + r.active.map(a => a[0] + ' ' + a[1].toFixed(4)).join(', ') + ']  ' +
    (r.span ? 'span ' + r.span[0] + '..' + r.span[1] + '  z ' + r.depth[0].toFixed(6) + ' .. ' + r.depth[r.depth.length - 1].toFixed(6) : 'no sample');
  location.hash = 'step=' + step;
}
function go(d) { step = Math.max(0, Math.min(T.rows.length, step + d)); draw(); }
document.getElementById('next').onclick = () => go(1);
document.getElementById('back').onclick = () => go(-1);
document.addEventListener('keydown', e => { if (e.key === 'ArrowRight') go(1); if (e.key === 'ArrowLeft') go(-1); });
draw();
</script></body></html>
"#;
