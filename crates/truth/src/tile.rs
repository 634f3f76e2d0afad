//! Binning and one tile: the opaque pass, the transparency pass, shading
//! and the box filter (SPEC §4, §8, §9, and supersampling).
//!
//! Prims are listed in the tiles their sample bounds touch, in draw order,
//! opaque and transparent apart. A tile then works on its own samples:
//! 1. Opaque pass: every covered sample keeps the nearest fragment — exact
//!    NC depth, strictly less than the stored one (cleared to 1.0), so of
//!    equal depths the first drawn wins. A sample of an alpha-masked
//!    texture below its cutoff is discarded before it can win.
//! 2. Transparency pass: every transparent fragment strictly nearer than
//!    the opaque one (and above the cutoff, if masked) is kept; per sample
//!    they are sorted by exact depth, farthest first (ties in draw order),
//!    and blended C = (1 − kt)·C_surface + kt·C_behind, 1 − kt being the
//!    opacity times the texel alpha where the texture's alpha blends. The
//!    fast renderer sorts whole triangles by mean depth instead; the two
//!    differ where transparent surfaces intersect or overlap out of order.
//! 3. Shading: the surviving opaque fragment (or the background, which is
//!    not fogged: the background colour, or the environment along the
//!    sample's ray when it is drawn, SPEC §5.3), each fragment lit and
//!    fogged before blending.
//! 4. The pixel is the mean of its n² sample colours, summed in a fixed
//!    order, so the image does not depend on threads or tiles.
//!
//! With diagnostics on, each sample also gets its distance in pixels to the
//! nearest place where the visible result can change abruptly, and how
//! fast its colour changes (see [`crate::Diagnostics`]).

use glam::{DVec2, DVec3};

use crate::coverage::{corner_bounds, EdgeValues, SampleRect, SampleTriangle};
use crate::frame::Frame;

/// Tile edge in pixels.
pub(crate) const TILE_PIXELS: u32 = 16;

/// Diagnostics look this far (pixels) for boundaries; farther is reported
/// as this value.
pub(crate) const DIAGNOSTIC_RANGE: f64 = 2.0;

/// Below this |N·L| the lighting counts as at its switch (distance 0).
/// The fast renderer's N·L is within ~10⁻⁶ of the exact value (f32
/// interpolation and normalization), so 10⁻⁴ leaves a wide margin.
const SWITCH_MARGIN: f64 = 1e-4;

/// Diagnostics move samples this far (pixels) to measure how fast their
/// colour changes: twice the largest shift (1/512 pixel per axis) that
/// snapping to a 1/256-pixel grid causes.
pub(crate) const SENSITIVITY_STEP: f64 = 1.0 / 256.0;

/// No fragment.
const NONE: u32 = u32::MAX;

/// Prims per tile, in draw order.
#[derive(Debug, Default)]
pub(crate) struct Bins {
    pub(crate) cols: u32,
    pub(crate) rows: u32,
    pub(crate) opaque: Vec<Vec<u32>>,
    pub(crate) transparent: Vec<Vec<u32>>,
}

/// Lists every prim in the tiles its sample bounds, widened by `margin`
/// samples, touch.
pub(crate) fn bin(frame: &Frame<'_>, margin: f64) -> Bins {
    let (cols, rows) = (frame.size.0.div_ceil(TILE_PIXELS), frame.size.1.div_ceil(TILE_PIXELS));
    let tiles = (cols * rows) as usize;
    let mut bins = Bins { cols, rows, opaque: vec![Vec::new(); tiles], transparent: vec![Vec::new(); tiles] };
    let tile = i64::from(TILE_PIXELS * frame.n);
    for (id, prim) in frame.prims.iter().enumerate() {
        let r = corner_bounds(&frame.geometry(prim).corners, frame.limit, margin);
        if r.is_empty() {
            continue;
        }
        let list = if frame.objects[prim.object as usize].transparent {
            &mut bins.transparent
        } else {
            &mut bins.opaque
        };
        for ty in r.y0 / tile..=(r.y1 - 1) / tile {
            for tx in r.x0 / tile..=(r.x1 - 1) / tile {
                list[(ty * i64::from(cols) + tx) as usize].push(id as u32);
            }
        }
    }
    bins
}

/// A tile's pixels (row-major within the tile) and, with diagnostics, their
/// boundary distances.
#[derive(Debug, Default)]
pub(crate) struct TileOutput {
    pub(crate) rgb: Vec<DVec3>,
    pub(crate) boundary: Vec<f32>,
    pub(crate) sensitivity: Vec<f32>,
}

/// A fragment kept for the transparency pass or the diagnostics.
#[derive(Clone, Copy, Debug)]
struct Fragment {
    sample: u32,
    z: f64,
    prim: u32,
}

/// Diagnostics being gathered: the boundary distance per sample (in
/// samples), and every fragment with its depth gradient.
type Gathered = (Vec<f64>, Vec<(Fragment, DVec2)>);

/// The samples of one tile and their buffers.
struct TileSamples<'f, 'a> {
    frame: &'f Frame<'a>,
    rect: SampleRect,
    depth: Vec<f64>,
    owner: Vec<u32>,
    diagnostics: Option<Gathered>,
}

/// Renders tile (`col`, `row`) of `bins`.
pub(crate) fn render_tile(
    frame: &Frame<'_>,
    bins: &Bins,
    col: u32,
    row: u32,
    diagnostics: bool,
) -> TileOutput {
    let tile = (row * bins.cols + col) as usize;
    let n = i64::from(frame.n);
    let px = (i64::from(col * TILE_PIXELS), i64::from(row * TILE_PIXELS));
    let pw = (i64::from(frame.size.0) - px.0).min(i64::from(TILE_PIXELS));
    let ph = (i64::from(frame.size.1) - px.1).min(i64::from(TILE_PIXELS));
    let rect = SampleRect { x0: px.0 * n, y0: px.1 * n, x1: (px.0 + pw) * n, y1: (px.1 + ph) * n };
    let len = ((pw * n) * (ph * n)) as usize;
    let mut t = TileSamples {
        frame,
        rect,
        depth: vec![1.0; len],
        owner: vec![NONE; len],
        diagnostics: diagnostics.then(|| (vec![DIAGNOSTIC_RANGE * n as f64; len], Vec::new())),
    };
    for &id in &bins.opaque[tile] {
        t.draw(id, |t, s, z, p| {
            if z < t.depth[s] && t.above_cutoff(id, p) {
                t.depth[s] = z;
                t.owner[s] = id;
            }
        });
    }
    let mut blended = Vec::new();
    for &id in &bins.transparent[tile] {
        t.draw(id, |t, s, z, p| {
            if z < t.depth[s] && t.above_cutoff(id, p) {
                blended.push(Fragment { sample: s as u32, z, prim: id });
            }
        });
    }
    blended.sort_by(|a, b| a.sample.cmp(&b.sample).then(b.z.total_cmp(&a.z)).then(a.prim.cmp(&b.prim)));
    t.resolve(&blended, (pw, ph))
}

impl TileSamples<'_, '_> {
    fn index(&self, x: i64, y: i64) -> usize {
        ((y - self.rect.y0) * (self.rect.x1 - self.rect.x0) + (x - self.rect.x0)) as usize
    }

    fn position(&self, s: usize) -> DVec2 {
        let w = (self.rect.x1 - self.rect.x0) as usize;
        DVec2::new((self.rect.x0 + (s % w) as i64) as f64 + 0.5, (self.rect.y0 + (s / w) as i64) as f64 + 0.5)
    }

    /// True unless prim `id` has an alpha cutoff its texel at `p` is below.
    fn above_cutoff(&self, id: u32, p: DVec2) -> bool {
        let object = &self.frame.objects[self.frame.prims[id as usize].object as usize];
        match object.texture.as_ref().and_then(|m| m.alpha_cutoff) {
            Some(cut) => self.frame.alpha(id, p) >= f64::from(cut),
            None => true,
        }
    }

    /// Calls `hit(self, sample, z, position)` for every sample of the tile
    /// that prim `id` covers; records diagnostics on the way.
    fn draw(&mut self, id: u32, mut hit: impl FnMut(&mut Self, usize, f64, DVec2)) {
        let frame = self.frame;
        let Some(tri) = SampleTriangle::new(frame.geometry(&frame.prims[id as usize]).corners) else {
            return;
        };
        let margin = if self.diagnostics.is_some() { DIAGNOSTIC_RANGE * f64::from(frame.n) } else { 0.0 };
        let r = tri.sample_bounds(frame.limit, margin).intersect(&self.rect);
        let gradient = tri.depth_gradient();
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                let p = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                let g: EdgeValues = tri.values(p);
                let s = self.index(x, y);
                if let Some((distance, _)) = &mut self.diagnostics {
                    distance[s] = distance[s].min(tri.boundary_distance(&g));
                }
                if !tri.covers(&g) {
                    continue;
                }
                let z = tri.depth(&tri.weights(&g));
                if let Some((_, fragments)) = &mut self.diagnostics {
                    fragments.push((Fragment { sample: s as u32, z, prim: id }, gradient));
                }
                hit(self, s, z, p);
            }
        }
    }

    /// The colour of sample `s` evaluated at position `p`: its opaque
    /// fragment (or the background) with its transparent fragments `frags`
    /// blended over it; `switch` is set when the lighting is at a switch.
    fn compose(&self, s: usize, p: DVec2, frags: &[Fragment], switch: &mut bool) -> DVec3 {
        let frame = self.frame;
        let mut color = if self.owner[s] != NONE {
            let shaded = frame.shade(self.owner[s], p);
            *switch |= shaded.switch_margin < SWITCH_MARGIN;
            shaded.color
        } else {
            frame.background(p)
        };
        for f in frags {
            let shaded = frame.shade(f.prim, p);
            let object = &frame.objects[frame.prims[f.prim as usize].object as usize];
            let alpha = match &object.texture {
                Some(m) if m.alpha_blend && m.alpha_cutoff.is_none() => shaded.alpha,
                _ => 1.0,
            };
            let keep = object.material.opacity * alpha;
            color = shaded.color * keep + color * (1.0 - keep);
            *switch |= shaded.switch_margin < SWITCH_MARGIN;
        }
        color
    }

    /// Diagnostics: the largest change of sample `s`'s colour, in 8-bit
    /// steps, when its position moves by [`SENSITIVITY_STEP`] pixels along
    /// x or y (the same fragments, shaded at the moved position).
    fn sensitivity(&self, s: usize, p: DVec2, frags: &[Fragment], color: DVec3) -> f64 {
        let step = SENSITIVITY_STEP * f64::from(self.frame.n);
        let moves = [DVec2::X, DVec2::NEG_X, DVec2::Y, DVec2::NEG_Y];
        let mut ignored = false;
        moves
            .iter()
            .map(|&m| {
                (self.compose(s, p + m * step, frags, &mut ignored) - color).abs().max_element() * 255.0
            })
            .fold(0.0, f64::max)
    }

    /// Shades, blends and box-filters the tile.
    fn resolve(mut self, blended: &[Fragment], (pw, ph): (i64, i64)) -> TileOutput {
        let len = self.depth.len();
        let mut colors = Vec::with_capacity(len);
        let mut switch = vec![false; len];
        let mut sensitivity = vec![0.0; if self.diagnostics.is_some() { len } else { 0 }];
        let mut rest = blended;
        for (s, at_switch) in switch.iter_mut().enumerate() {
            let count = rest.iter().take_while(|f| f.sample as usize == s).count();
            let (frags, tail) = rest.split_at(count);
            rest = tail;
            let p = self.position(s);
            let color = self.compose(s, p, frags, at_switch);
            if let Some(v) = sensitivity.get_mut(s) {
                *v = self.sensitivity(s, p, frags, color);
            }
            colors.push(color);
        }
        let n = self.frame.n as usize;
        let w = (self.rect.x1 - self.rect.x0) as usize;
        let mut out = TileOutput::default();
        let distances = self.diagnostics.take().map(|d| self.distances(d, &switch));
        for py in 0..ph as usize {
            for px in 0..pw as usize {
                let samples = (0..n * n).map(|k| (py * n + k / n) * w + px * n + k % n);
                let sum: DVec3 = samples.clone().map(|s| colors[s]).sum();
                out.rgb.push(sum / (n * n) as f64);
                if let Some(d) = &distances {
                    let nearest = samples.clone().map(|s| d[s]).fold(f64::INFINITY, f64::min);
                    out.boundary.push((nearest / n as f64) as f32);
                    out.sensitivity.push(samples.map(|s| sensitivity[s]).fold(0.0, f64::max) as f32);
                }
            }
        }
        out
    }

    /// Per sample (in samples): the smaller of the edge distance and the
    /// distance to a change of depth order that matters; 0 at a lighting
    /// switch.
    fn distances(&self, (mut d, mut fragments): Gathered, switch: &[bool]) -> Vec<f64> {
        fragments.sort_by(|a, b| a.0.sample.cmp(&b.0.sample).then(a.0.z.total_cmp(&b.0.z)));
        for group in fragments.chunk_by(|a, b| a.0.sample == b.0.sample) {
            let s = group[0].0.sample as usize;
            let owner = self.owner[s];
            let visible = group.iter().find(|f| f.0.prim == owner);
            for (k, f) in group.iter().enumerate() {
                // The visible opaque fragment against every other one, and
                // consecutive fragments nearer than it (the blending order).
                if let Some(v) = visible {
                    if f.0.prim != owner {
                        d[s] = d[s].min(order_distance(v, f));
                    }
                }
                let in_front = visible.is_none_or(|v| f.0.z <= v.0.z);
                if k > 0 && in_front && group[k - 1].0.prim != owner {
                    d[s] = d[s].min(order_distance(&group[k - 1], f));
                }
            }
        }
        for (d, &at_switch) in d.iter_mut().zip(switch) {
            if at_switch {
                *d = 0.0;
            }
        }
        d
    }
}

/// How far (in samples) a sample is from the point where fragments `a` and
/// `b` swap depth order: |Δz| over |∇z_a − ∇z_b| + |∇z_a| + |∇z_b|. The
/// second part is how fast a plane moves when its vertices move, so the
/// distance also bounds how far vertices must move to swap the order. The
/// gap is first reduced by four f32 units of depth (the fast renderer
/// stores depth in f32).
fn order_distance(a: &(Fragment, DVec2), b: &(Fragment, DVec2)) -> f64 {
    let gap = (a.0.z - b.0.z).abs() - 4.0 * f64::from(f32::EPSILON) * a.0.z.abs().max(b.0.z.abs());
    if gap <= 0.0 {
        return 0.0;
    }
    let rate = (a.1 - b.1).length() + a.1.length() + b.1.length();
    if rate > 0.0 {
        gap / rate
    } else {
        f64::INFINITY
    }
}
