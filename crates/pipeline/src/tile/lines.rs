//! Drawing a tile's lines ([`crate::lines`]) after its surfaces, and the
//! depth-only pass that decides which lines are hidden when surfaces are
//! not drawn (lines alone) or leave no depth (the painter's algorithm).

use zline_raster::{for_each_block, AttributePlanes, DepthPlane, EdgeTable, LANES};
use zline_scene::WireframeMode;
use zline_simd::lanes::{f32x8, Baseline};

use super::target::{store, TileTarget};
use crate::lines::{Lines, Segment, DASH_ON, DASH_PERIOD};
use crate::setup::{Kernel, KernelTables, PrimitiveChunk, TexturedLighting};

impl TileTarget {
    /// Writes the depth of primitives (chunk, kernel, table index) into the
    /// depth buffer, nearest kept, without touching the colour: the
    /// z-buffer of the opaque pass without shading. Alpha-masked texels
    /// are not cut out here.
    pub fn depth_only_pass(
        &mut self,
        chunks: &[PrimitiveChunk],
        primitives: impl Iterator<Item = (u32, Kernel, u32)>,
    ) {
        let (rect, origin, stride) = (self.rect, self.origin, self.stride);
        let zbuf: &mut [f32] = bytemuck::cast_slice_mut(&mut self.depth);
        for (chunk, kernel, index) in primitives {
            let (edges, depth) = edges_and_depth(&chunks[chunk as usize].tables, kernel, index as usize);
            edges.scan(rect, |span| {
                let row = (span.y - rect.y0) as usize * stride;
                for_each_block(depth, &AttributePlanes::NONE, span, |b| {
                    let i = row + (b.x - origin) as usize;
                    for (k, &z) in b.z.iter().enumerate() {
                        if b.mask & (1 << k) != 0 && z < zbuf[i + k] {
                            zbuf[i + k] = z;
                        }
                    }
                });
            });
        }
    }

    /// Sets every sample's colour to the background (lines alone).
    pub fn fill_background(&mut self) {
        for i in (0..self.depth.len() * LANES).step_by(LANES) {
            let bg = self.background_block::<Baseline>(i);
            let [red, green, blue] = &mut self.rgb;
            for (plane, c) in [(red, bg.x), (green, bg.y), (blue, bg.z)] {
                store(plane, i, c);
            }
        }
        if self.coverage {
            self.alpha.iter_mut().for_each(|a| *a = f32x8::ZERO);
        }
        self.colors_valid = true;
    }

    /// Draws the segments `bin` of `lines` (see [`crate::lines`] for the
    /// pixel rule, the visibility test and the dashes) into the tile, whose
    /// rect holds `n` × `n` samples per pixel.
    pub fn line_pass(&mut self, lines: &Lines, bin: &[u32], n: u32) {
        if bin.is_empty() {
            return;
        }
        if !self.colors_valid {
            self.materialize_background::<Baseline>();
        }
        for &k in bin {
            self.segment(&lines.segments[k as usize], lines, n);
        }
    }

    fn segment(&mut self, s: &Segment, lines: &Lines, n: u32) {
        let (dx, dy) = (s.b[0] - s.a[0], s.b[1] - s.a[1]);
        // Major axis m, minor axis o.
        let (m, o) = if dx.abs() >= dy.abs() { (0, 1) } else { (1, 0) };
        let (dm, d_o) = if m == 0 { (dx, dy) } else { (dy, dx) };
        if dm == 0.0 || !dm.is_finite() || !d_o.is_finite() {
            return;
        }
        let ni = n as i32;
        let r = self.rect;
        let (lo, hi) = if m == 0 { ((r.x0, r.x1), (r.y0, r.y1)) } else { ((r.y0, r.y1), (r.x0, r.x1)) };
        let (lo, hi) = ((lo.0 / ni, lo.1 / ni), (hi.0 / ni, hi.1 / ni));
        let (from, to) = (s.a[m].min(s.b[m]), s.a[m].max(s.b[m]));
        // Columns whose centre c = i + ½ lies in [from, to).
        let first = ((from - 0.5).ceil().max(f64::from(lo.0))) as i32;
        let last = ((to - 0.5).ceil().min(f64::from(lo.1))) as i32;
        for i in first..last {
            let t = (f64::from(i) + 0.5 - s.a[m]) / dm;
            let j = (s.a[o] + t * d_o).floor();
            if !(f64::from(hi.0)..f64::from(hi.1)).contains(&j) {
                continue;
            }
            let z = s.z[0] + t * (s.z[1] - s.z[0]);
            let on = i.rem_euclid(DASH_PERIOD) < DASH_ON;
            let (px, py) = if m == 0 { (i, j as i32) } else { (j as i32, i) };
            self.line_pixel((px, py), ni, z - s.tolerance, (lines.mode, on), lines.color);
        }
    }

    /// The n × n samples of pixel (px, py): each drawn when the mode says
    /// so for its visibility (`limit` is the line's depth less its
    /// tolerance: visible when no nearer than the stored depth).
    #[inline]
    fn line_pixel(
        &mut self,
        (px, py): (i32, i32),
        n: i32,
        limit: f64,
        (mode, dash_on): (WireframeMode, bool),
        color: glam::Vec3,
    ) {
        for sy in py * n..(py + 1) * n {
            for sx in px * n..(px + 1) * n {
                let i = self.index(sx, sy);
                let stored = f64::from(super::sample(&self.depth, i));
                let visible = limit <= stored;
                let drawn = match mode {
                    WireframeMode::None => false,
                    WireframeMode::All => true,
                    WireframeMode::HiddenRemoved => visible,
                    WireframeMode::HiddenDashed => visible || dash_on,
                };
                if drawn {
                    for (plane, c) in self.rgb.iter_mut().zip([color.x, color.y, color.z]) {
                        bytemuck::cast_slice_mut::<f32x8, f32>(plane)[i] = c;
                    }
                    if self.coverage {
                        bytemuck::cast_slice_mut::<f32x8, f32>(&mut self.alpha)[i] = 1.0;
                    }
                }
            }
        }
    }
}

/// A primitive's edge table and depth plane, whatever its kernel.
fn edges_and_depth(t: &KernelTables, kernel: Kernel, i: usize) -> (&EdgeTable, &DepthPlane) {
    match kernel {
        Kernel::Flat => (&t.flat[i].edges, &t.flat[i].depth),
        Kernel::Gouraud { .. } => (&t.gouraud[i].edges, &t.gouraud[i].depth),
        Kernel::Phong(_) => (&t.phong[i].edges, &t.phong[i].depth),
        Kernel::ColoredPhong(_) => (&t.colored_phong[i].edges, &t.colored_phong[i].depth),
        Kernel::Perturbed { .. } => (&t.perturbed[i].edges, &t.perturbed[i].depth),
        Kernel::Textured { lighting, .. } => match lighting {
            TexturedLighting::Flat => (&t.textured_flat[i].edges, &t.textured_flat[i].depth),
            TexturedLighting::Gouraud => (&t.textured_gouraud[i].edges, &t.textured_gouraud[i].depth),
            TexturedLighting::Phong => (&t.textured_phong[i].edges, &t.textured_phong[i].depth),
            TexturedLighting::ColoredPhong => {
                (&t.textured_colored_phong[i].edges, &t.textured_colored_phong[i].depth)
            }
        },
    }
}
