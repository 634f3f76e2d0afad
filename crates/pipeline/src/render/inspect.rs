//! The pixel inspector: every fragment that touched one pixel, in the order
//! the renderer drew it, and what each did to the pixel's samples.
//!
//! It is the renderer itself, not a model of it. The frame is rendered as
//! usual (geometry, setup, binning, every tile), then the tile holding the
//! pixel is drawn once more with the same passes, the same kernels and the
//! same primitives in the same order, one primitive per call: the opaque
//! pass, the fog pass and the transparency pass (or the painter's pass)
//! each keep their order, and a kernel drawing one primitive does to a
//! sample exactly what it does inside the whole bin. Between calls the
//! inspector reads each of the pixel's samples from the tile's buffers:
//! the depth and colour before and after every primitive that covers it.
//! The tile is then resolved as usual; its pixel is checked against the
//! rendered image's (`PixelTrace::matches`), which the tests require bit
//! for bit.
//!
//! Beside the buffers, each fragment reports what the renderer computed to
//! decide it: the primitive's edge table (its window vertices on the
//! 1/256-pixel grid and the span that covers the sample on its row, with
//! whether the sample lies exactly on an edge, where the top-left rule
//! decided), the depth interpolated at the sample by the same incremental
//! evaluation the kernels use (`zline_raster::for_each_sample`, the scalar
//! twin of their blocks), and the depth test's verdict.

use glam::{Vec2, Vec3};
use zline_raster::{covers, for_each_sample, AttributePlanes, DepthPlane, Rect, Span, TieRule};
use zline_scene::Scene;

use super::tiles::TilePasses;
use super::{Frame, RenderOptions, Renderer};
use crate::bin::{OpaqueRef, PrimitiveRef, TileGrid};
use crate::image::{Image, ImageRows};
use crate::setup::{layout, Kernel, KernelTables, PassKind, PrimitiveChunk, TexturedLighting};
use crate::tile::{FrameTexture, TileTarget};

/// The pass that drew a fragment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// The opaque pass: depth-tested, depth and colour written.
    Opaque,
    /// The transparency pass: depth-tested against the opaque depth,
    /// blended, no depth written.
    Transparent,
    /// The painter's algorithm: painted in sorted order, no depth test.
    Painter,
}

/// What a fragment did to its sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Passed the depth test; its depth and colour were written.
    Written,
    /// Failed the depth test (z ≥ the stored depth): hidden.
    Hidden,
    /// Passed the depth test but left the sample as it was: discarded by
    /// a texture's alpha cutoff.
    Discarded,
    /// Blended over the sample (a transparent surface, or the painter's).
    Blended,
}

/// One fragment: one primitive at one sample.
#[derive(Clone, Debug, PartialEq)]
pub struct FragmentTrace {
    /// The pass that drew it.
    pub pass: Pass,
    /// The object (its index in `Scene::objects`).
    pub object: u32,
    /// The triangle of the object's mesh that made the primitive (a
    /// clipped triangle makes several), when known.
    pub triangle: Option<u32>,
    /// The kernel that drew it.
    pub kernel: Kernel,
    /// The primitive's window vertices in pixels, as snapped to the
    /// 1/256-sample grid, top to bottom.
    pub vertices: [(f64, f64); 3],
    /// The span that covers the sample on its row (in samples: the edge
    /// table's half-open columns `x0..x1` of row `y`).
    pub span: Span,
    /// True when the sample lies exactly on one of the primitive's edges:
    /// the top-left rule decided it is in.
    pub on_edge: bool,
    /// The NC depth interpolated at the sample.
    pub z: f32,
    /// ∂z/∂x along the row: the span's depth steps by it from sample to
    /// sample (SPEC §4).
    pub dzdx: f64,
    /// The sample's depth and linear colour before and after.
    pub before: (f32, Vec3),
    /// See `before`.
    pub after: (f32, Vec3),
    /// What it did.
    pub outcome: Outcome,
    /// The primitive's interpolated values at the sample.
    pub attributes: SampleAttributes,
    /// Per light of the scene, the share of it the sample sees: the
    /// shadow maps' own lookup, or 0 where the sample's planar shadow bit
    /// for the light is set (1 elsewhere); empty for kernels without a
    /// per-sample normal (flat, Gouraud).
    pub light_shares: Vec<f32>,
}

/// What a primitive's attribute planes give at one sample, evaluated as
/// the kernels evaluate them (incrementally along the span) and divided by
/// the 1/w plane as they divide (v / q; q = 1 screen-linear). Each is
/// present only where the primitive's kernel interpolates it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SampleAttributes {
    /// The eye-space normal, as interpolated (before renormalizing).
    pub normal: Option<Vec3>,
    /// The eye-space position.
    pub eye: Option<Vec3>,
    /// The texture coordinates (s, t).
    pub uv: Option<Vec2>,
    /// A vertex colour, interpolated.
    pub vertex_color: Option<Vec3>,
    /// Gouraud shading's lit colour, interpolated from the vertices.
    pub gouraud: Option<Vec3>,
    /// The lighting parts a textured flat or Gouraud kernel multiplies
    /// with the texel: (ambient + diffuse, specular).
    pub lit_parts: Option<(Vec3, Vec3)>,
    /// Flat shading's colour, lit once at the centroid.
    pub flat: Option<Vec3>,
    /// The diffuse texture read at the sample.
    pub texture: Option<TextureRead>,
}

/// A texture read at one sample, by the sampler's scalar twin
/// (`Texture::sample`, bit for bit the kernels' eight-lane read).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRead {
    /// The texture's size (level 0).
    pub size: (u32, u32),
    /// Its mip levels.
    pub levels: usize,
    /// The filter.
    pub filter: zline_shading::Filter,
    /// The level of detail (trilinear filtering: ½·log2 of the larger
    /// squared footprint in texels, from the planes' exact derivatives, in
    /// scalar f32 — the kernels take the same formula eight lanes at a
    /// time with a vector log2, so the last bits may differ; 0 for nearest
    /// and bilinear filtering).
    pub lod: f32,
    /// The filtered texel (RGBA, linear).
    pub texel: glam::Vec4,
}

/// The planes of one primitive at sample `x` of `span`, over q.
fn planes_at<const N: usize>(
    depth: &DepthPlane,
    planes: &AttributePlanes<N>,
    span: Span,
    x: i32,
) -> [f32; N] {
    let mut values = [0.0; N];
    for_each_sample(depth, planes, span, |sx, _, v| {
        if sx == x {
            values = *v;
        }
    });
    let q = values.first().copied().unwrap_or(1.0);
    values.map(|v| v / q)
}

fn vec3(v: &[f32], at: usize) -> Vec3 {
    Vec3::new(v[at], v[at + 1], v[at + 2])
}

/// The texture `texture` read at (s, t) with the level of detail `lod`
/// names, the derivatives from `planes` (the textured layout).
fn read_texture<const N: usize>(
    textures: &[FrameTexture],
    (texture, lod, interpolation): (u32, crate::setup::LevelOfDetail, zline_scene::Interpolation),
    (depth, planes): (&DepthPlane, &AttributePlanes<N>),
    (span, x): (Span, i32),
) -> Option<TextureRead> {
    use layout::textured::{Q, S, T};
    let f = textures.get(texture as usize)?;
    let mut raw = [0.0f32; N];
    for_each_sample(depth, planes, span, |sx, _, v| {
        if sx == x {
            raw = *v;
        }
    });
    let inv = 1.0 / raw[Q];
    let (s, t) = (raw[S] * inv, raw[T] * inv);
    let (w, h) = (f.texture.width(), f.texture.height());
    let level = match lod {
        crate::setup::LevelOfDetail::Base => 0.0,
        crate::setup::LevelOfDetail::Derivatives => {
            let (dx, dy) = (planes.dx(), planes.dy());
            let perspective = interpolation == zline_scene::Interpolation::PerspectiveCorrect;
            let d = |ds: f32, dq: f32, v: f32| if perspective { (ds - v * dq) * inv } else { ds };
            let (sx, tx) = (d(dx[S], dx[Q], s) * w as f32, d(dx[T], dx[Q], t) * h as f32);
            let (sy, ty) = (d(dy[S], dy[Q], s) * w as f32, d(dy[T], dy[Q], t) * h as f32);
            0.5 * (sx * sx + tx * tx).max(sy * sy + ty * ty).log2()
        }
    };
    Some(TextureRead {
        size: (w, h),
        levels: f.texture.levels(),
        filter: f.sampler.filter,
        lod: level,
        texel: f.texture.sample(&f.sampler, s, t, level),
    })
}

/// The attributes of primitive `index` of `kernel` at sample `x` of `span`.
fn attributes_of(
    (t, textures): (&KernelTables, &[FrameTexture]),
    kernel: Kernel,
    index: u32,
    span: Span,
    x: i32,
) -> SampleAttributes {
    use layout::{gouraud, phong, textured};
    let i = index as usize;
    let mut a = SampleAttributes::default();
    if let Kernel::Textured { lighting, interpolation, lod, .. } = kernel {
        let how = |id: u32| (id, lod, interpolation);
        let at = (span, x);
        a.texture = match lighting {
            TexturedLighting::Flat => {
                let p = &t.textured_flat[i];
                read_texture(textures, how(p.shader.texture), (&p.depth, &p.shader.planes), at)
            }
            TexturedLighting::Gouraud => {
                let p = &t.textured_gouraud[i];
                read_texture(textures, how(p.shader.texture), (&p.depth, &p.shader.planes), at)
            }
            TexturedLighting::Phong => {
                let p = &t.textured_phong[i];
                read_texture(textures, how(p.shader.texture), (&p.depth, &p.shader.planes), at)
            }
            TexturedLighting::ColoredPhong => {
                let p = &t.textured_colored_phong[i];
                read_texture(textures, how(p.shader.texture), (&p.depth, &p.shader.planes), at)
            }
        };
    }
    let phong_like = |a: &mut SampleAttributes, v: &[f32], normal: usize, eye: usize| {
        (a.normal, a.eye) = (Some(vec3(v, normal)), Some(vec3(v, eye)));
    };
    match kernel {
        Kernel::Flat => a.flat = Some(t.flat[i].shader.color),
        Kernel::Gouraud { .. } => {
            let p = &t.gouraud[i];
            a.gouraud = Some(vec3(&planes_at(&p.depth, &p.shader.planes, span, x), gouraud::COLOR));
        }
        Kernel::Phong(_) => {
            let p = &t.phong[i];
            phong_like(&mut a, &planes_at(&p.depth, &p.shader.planes, span, x), phong::NORMAL, phong::EYE);
        }
        Kernel::ColoredPhong(_) => {
            let p = &t.colored_phong[i];
            let v = planes_at(&p.depth, &p.shader.planes, span, x);
            phong_like(&mut a, &v, phong::NORMAL, phong::EYE);
            a.vertex_color = Some(vec3(&v, phong::COLOR));
        }
        Kernel::Textured { lighting, .. } => {
            let uv = |v: &[f32]| Some(Vec2::new(v[textured::S], v[textured::T]));
            match lighting {
                TexturedLighting::Flat => {
                    let p = &t.textured_flat[i];
                    a.uv = uv(&planes_at(&p.depth, &p.shader.planes, span, x));
                    a.lit_parts = Some((p.shader.ambient_diffuse, p.shader.specular));
                }
                TexturedLighting::Gouraud => {
                    let p = &t.textured_gouraud[i];
                    let v = planes_at(&p.depth, &p.shader.planes, span, x);
                    a.uv = uv(&v);
                    a.lit_parts = Some((vec3(&v, textured::AMBIENT_DIFFUSE), vec3(&v, textured::SPECULAR)));
                }
                TexturedLighting::Phong => {
                    let p = &t.textured_phong[i];
                    let v = planes_at(&p.depth, &p.shader.planes, span, x);
                    a.uv = uv(&v);
                    phong_like(&mut a, &v, textured::NORMAL, textured::EYE);
                }
                TexturedLighting::ColoredPhong => {
                    let p = &t.textured_colored_phong[i];
                    let v = planes_at(&p.depth, &p.shader.planes, span, x);
                    a.uv = uv(&v);
                    phong_like(&mut a, &v, textured::NORMAL, textured::EYE);
                    a.vertex_color = Some(vec3(&v, textured::COLOR));
                }
            }
        }
        Kernel::Perturbed { .. } => {
            let p = &t.perturbed[i];
            let v = planes_at(&p.depth, &p.shader.planes, span, x);
            a.uv = Some(Vec2::new(v[layout::perturbed::S], v[layout::perturbed::T]));
            phong_like(&mut a, &v, layout::perturbed::NORMAL, layout::perturbed::EYE);
        }
    }
    a
}

/// One sample of the pixel and every fragment at it.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleTrace {
    /// The sample's position in window pixels.
    pub position: (f64, f64),
    /// The fragments, in the order drawn.
    pub fragments: Vec<FragmentTrace>,
    /// Depth and colour after the opaque pass (the painter's: after it).
    pub after_opaque: (f32, Vec3),
    /// The colour after the fog pass, when the scene has fog.
    pub after_fog: Option<Vec3>,
    /// Depth, colour and alpha as the resolve reads them.
    pub last: (f32, Vec3, f32),
}

/// The inspector's report on one pixel (see the module's documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct PixelTrace {
    /// The pixel.
    pub pixel: (u32, u32),
    /// Samples per pixel side (`ssaa`).
    pub n: u32,
    /// The pixel's samples, row by row.
    pub samples: Vec<SampleTrace>,
    /// The far depth: a sample still at it was never drawn.
    pub far: f32,
    /// The tone mapping the resolve applies before quantizing.
    pub tone: zline_shading::ToneMapping,
    /// The inspector's resolve of the pixel (RGBA bytes).
    pub resolved: [u8; 4],
    /// The rendered image's pixel (RGBA bytes).
    pub image: [u8; 4],
    /// Why fragments could not be followed, if they could not (only the
    /// lines of `--wireframe-only` are drawn then).
    pub note: Option<String>,
}

impl PixelTrace {
    /// True when the inspector's pixel is the rendered image's, byte for
    /// byte.
    pub fn matches(&self) -> bool {
        self.resolved == self.image
    }
}

/// The pixel (`x`, `y`) is outside the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutsideImage {
    /// The pixel asked for.
    pub pixel: (u32, u32),
    /// The image's size.
    pub size: (u32, u32),
}

impl std::fmt::Display for OutsideImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ((x, y), (w, h)) = (self.pixel, self.size);
        write!(f, "pixel ({x}, {y}) is outside the {w}x{h} image (x in 0..{w}, y in 0..{h})")
    }
}

impl std::error::Error for OutsideImage {}

impl Renderer {
    /// Renders `scene` into `image` and follows pixel `pixel` through the
    /// frame (see the module's documentation).
    pub fn inspect(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        pixel: (u32, u32),
        image: &mut Image,
    ) -> Result<PixelTrace, OutsideImage> {
        let size = (scene.settings.width, scene.settings.height);
        if pixel.0 >= size.0 || pixel.1 >= size.1 {
            return Err(OutsideImage { pixel, size });
        }
        self.normals = false;
        self.probe = Some(pixel);
        self.render_frame(scene, options, image, None);
        self.probe = None;
        // The frame's primitives and bins are still the renderer's; the
        // frame and its tile grid are made again as `render_frame` made
        // them.
        let frame = Frame::new(scene);
        let tile_size = options.tile_size.clamp(1, zline_scene::MAX_TILE_SIZE);
        let grid = TileGrid::new(frame.viewport.width, frame.viewport.height, tile_size * frame.n);
        Ok(self.trace_pixel(scene, &frame, &grid, pixel, image))
    }

    /// Draws the tile holding `pixel` again, one primitive per call,
    /// reading the pixel's samples between them.
    fn trace_pixel(
        &self,
        scene: &Scene,
        frame: &Frame,
        grid: &TileGrid,
        pixel: (u32, u32),
        image: &Image,
    ) -> PixelTrace {
        let passes = self.tile_passes(scene, frame, grid, false);
        let n = frame.n;
        let (sx0, sy0) = ((pixel.0 * n) as i32, (pixel.1 * n) as i32);
        let (col, row) = (sx0 as u32 / grid.tile_size, sy0 as u32 / grid.tile_size);
        let tile = row as usize * grid.cols as usize + col as usize;
        let rect = grid.rect(col, row);
        let mut target = TileTarget::default();
        target.set_coverage(passes.coverage);
        target.reserve(grid.tile_size, !self.bins.shadow[tile].is_empty());
        target.clear(rect, passes.background.0, passes.clear);
        target.paint_sky(passes.sky.as_ref());
        target.ceiling = passes.shade.lighting.ceiling();
        let positions: Vec<(i32, i32)> =
            (0..n as i32).flat_map(|b| (0..n as i32).map(move |a| (sx0 + a, sy0 + b))).collect();
        let mut probe = Probe {
            passes: &passes,
            lights: scene.lights.len(),
            textures: &self.tables.textures,
            positions: &positions,
            n,
            fragments: vec![Vec::new(); positions.len()],
        };
        let (opaque, transparent) = (&self.bins.opaque[tile], &self.bins.transparent[tile]);
        let mut order = Vec::new();
        let mut note = None;
        let (after_opaque, after_fog) = if passes.lines_only && passes.lines.is_some() {
            target
                .depth_only_pass(passes.chunks, super::opaque_primitives(passes.chunks, opaque, transparent));
            target.fill_background();
            note = Some("--wireframe-only: the surfaces only hide lines; no fragment is shaded".into());
            (probe.states(&target), None)
        } else if passes.painter {
            target.shadow_pass(passes.chunks, &self.bins.shadow[tile]);
            let fog = passes.fog.as_ref();
            for r in sorted(passes.chunks, transparent, |d| d.far_depth) {
                probe.draw(&mut target, Pass::Painter, r, |t| {
                    t.painter_pass(passes.chunks, &[r], &passes.shade, fog, &mut order);
                });
            }
            let painted = probe.states(&target);
            // Hidden lines need the depth the painter does not keep.
            if passes.lines.is_some_and(|l| l.mode.hides() && !l.bin_of(tile).is_empty()) {
                target.depth_only_pass(
                    passes.chunks,
                    super::opaque_primitives(passes.chunks, opaque, transparent),
                );
            }
            (painted, None)
        } else {
            target.shadow_pass(passes.chunks, &self.bins.shadow[tile]);
            for r in opaque {
                let r_ref = draw_ref(passes.chunks, r);
                probe.draw(&mut target, Pass::Opaque, r_ref, |t| {
                    t.opaque_pass(passes.chunks, std::slice::from_ref(r), &passes.shade);
                });
            }
            let after_opaque = probe.states(&target);
            let after_fog = passes.fog.as_ref().map(|fog| {
                target.fog_pass(fog);
                probe.states(&target).into_iter().map(|(_, c, _)| c).collect::<Vec<_>>()
            });
            let fog = passes.fog.as_ref();
            for r in sorted(passes.chunks, transparent, |d| d.sort_depth) {
                probe.draw(&mut target, Pass::Transparent, r, |t| {
                    t.transparency_pass(passes.chunks, &[r], &passes.shade, fog, &mut order);
                });
            }
            (after_opaque, after_fog)
        };
        if let Some(lines) = passes.lines {
            target.line_pass(lines, lines.bin_of(tile), n);
        }
        target.tone = passes.tone;
        let last = probe.states(&target);
        let width = frame.width as usize;
        let tile_rows = (rect.height() as u32).div_ceil(n) as usize;
        let mut band = vec![0u32; width * tile_rows];
        let mut rows = ImageRows::whole(&mut band, width);
        match (passes.coverage, n) {
            (false, 1) => target.resolve(&mut rows),
            (false, _) => target.resolve_supersampled(&mut rows, n),
            (true, 1) => target.resolve_coverage(&mut rows),
            (true, _) => target.resolve_coverage_supersampled(&mut rows, n),
        }
        let local_row = (pixel.1 - (rect.y0 as u32) / n) as usize;
        let resolved = band[local_row * width + pixel.0 as usize].to_le_bytes();
        let at = pixel.1 as usize * image.width as usize + pixel.0 as usize;
        let samples = positions
            .iter()
            .zip(probe.fragments)
            .enumerate()
            .map(|(i, (&(x, y), fragments))| SampleTrace {
                position: ((f64::from(x) + 0.5) / f64::from(n), (f64::from(y) + 0.5) / f64::from(n)),
                fragments,
                after_opaque: (after_opaque[i].0, after_opaque[i].1),
                after_fog: after_fog.as_ref().map(|c| c[i]),
                last: last[i],
            })
            .collect();
        PixelTrace {
            pixel,
            n,
            samples,
            far: passes.clear,
            tone: passes.tone,
            resolved,
            image: image.pixels[at].to_le_bytes(),
            note,
        }
    }
}

/// A bin's primitives in the order a sorting pass draws them: `key` far to
/// near, ties in draw order (the passes' own sort, `tile::back_to_front`).
fn sorted(
    chunks: &[PrimitiveChunk],
    bin: &[PrimitiveRef],
    key: impl Fn(&crate::setup::Draw) -> f32,
) -> Vec<PrimitiveRef> {
    let mut order = Vec::new();
    let keyed = bin.iter().map(|r| (key(&chunks[r.chunk as usize].draws[r.index as usize]), *r));
    crate::tile::back_to_front(&mut order, keyed);
    order.into_iter().map(|(_, r)| r).collect()
}

/// The draw-list entry of an opaque bin's reference.
fn draw_ref(chunks: &[PrimitiveChunk], r: &OpaqueRef) -> PrimitiveRef {
    let draws = &chunks[r.chunk as usize].draws;
    let index = draws.iter().position(|d| d.kernel == r.kernel && d.index == r.index).unwrap_or(0);
    PrimitiveRef { chunk: r.chunk, index: index as u32 }
}

/// The pixel's samples, followed through the calls.
struct Probe<'a> {
    passes: &'a TilePasses<'a>,
    /// The scene's lights.
    lights: usize,
    textures: &'a [FrameTexture],
    positions: &'a [(i32, i32)],
    n: u32,
    fragments: Vec<Vec<FragmentTrace>>,
}

impl Probe<'_> {
    fn states(&self, target: &TileTarget) -> Vec<(f32, Vec3, f32)> {
        self.positions.iter().map(|&(x, y)| target.sample_state(x, y)).collect()
    }

    /// Draws one primitive with `call`, recording a fragment at each of
    /// the pixel's samples it covers.
    fn draw(
        &mut self,
        target: &mut TileTarget,
        pass: Pass,
        r: PrimitiveRef,
        call: impl FnOnce(&mut TileTarget),
    ) {
        let chunk = &self.passes.chunks[r.chunk as usize];
        let d = chunk.draws[r.index as usize];
        let (edges, depth) = chunk.tables.coverage(d.kernel, d.index);
        let covered: Vec<Option<Span>> = self
            .positions
            .iter()
            .map(|&(x, y)| {
                let mut span = None;
                edges.scan(Rect { x0: i32::MIN / 2, y0: y, x1: i32::MAX / 2, y1: y + 1 }, |s| span = Some(s));
                span.filter(|s| (s.x0..s.x1).contains(&x))
            })
            .collect();
        if covered.iter().all(Option::is_none) {
            call(target);
            return;
        }
        let before = self.states(target);
        let masks: Vec<i32> = self.positions.iter().map(|&(x, y)| target.shadow_mask_at(x, y)).collect();
        call(target);
        let after = self.states(target);
        let triangle = triangle_of(chunk, r.index);
        let scale = 256.0 * f64::from(self.n);
        let vertices = edges.sorted_vertices().map(|p| (f64::from(p.x) / scale, f64::from(p.y) / scale));
        let blends = matches!(chunk.pass, PassKind::Transparent { .. }) || pass == Pass::Painter;
        for (i, span) in covered.into_iter().enumerate() {
            let Some(span) = span else { continue };
            let (x, y) = self.positions[i];
            let mut z = f32::NAN;
            for_each_sample(depth, &AttributePlanes::NONE, span, |sx, sz, _| {
                if sx == x {
                    z = sz;
                }
            });
            let on_edge = {
                let v = edges.sorted_vertices();
                covers(v, x.into(), y.into(), TieRule::Closed) != covers(v, x.into(), y.into(), TieRule::Open)
            };
            let (b, a) = ((before[i].0, before[i].1), (after[i].0, after[i].1));
            let attributes = attributes_of((&chunk.tables, self.textures), d.kernel, d.index, span, x);
            let material = self.passes.shade.materials.get(chunk.object as usize);
            let light_shares =
                light_shares(&self.passes.shade, (masks[i], material), &attributes, self.lights);
            // The kernels' test: z < stored (NaN fails).
            let passed = z < b.0;
            let outcome = match pass {
                Pass::Painter => Outcome::Blended,
                _ if !passed => Outcome::Hidden,
                _ if blends => Outcome::Blended,
                _ if a.0 == z => Outcome::Written,
                _ => Outcome::Discarded,
            };
            self.fragments[i].push(FragmentTrace {
                pass,
                object: chunk.object,
                triangle,
                kernel: d.kernel,
                vertices,
                span,
                on_edge,
                z,
                dzdx: depth.dzdx(),
                before: b,
                after: a,
                outcome,
                attributes,
                light_shares,
            });
        }
    }
}

/// Per light, the share a sample sees (see `FragmentTrace::light_shares`):
/// the kernels' own lookups, `ShadowMaps::visibility_x8` at the sample's
/// position and unit normal, or the planar mask's bit for the light.
fn light_shares(
    shade: &crate::tile::ShadeContext<'_>,
    (mask, material): (i32, Option<&zline_shading::PreparedMaterial>),
    a: &SampleAttributes,
    lights: usize,
) -> Vec<f32> {
    use zline_shading::Vec3x8;
    use zline_simd::lanes::Baseline;
    let (Some(normal), Some(point)) = (a.normal, a.eye) else { return Vec::new() };
    let normal = normal.normalize_or_zero();
    (0..lights as u32)
        .map(|k| match (shade.maps, material.and_then(|m| m.shadow_bits)) {
            (Some(maps), _) => {
                let lanes = (Vec3x8::<Baseline>::splat(point), Vec3x8::<Baseline>::splat(normal));
                maps.visibility_x8(k, lanes.0, lanes.1).to_array()[0]
            }
            (None, Some(first)) => match first.checked_add(k).filter(|&b| b < 32) {
                Some(bit) if mask & (1 << bit) != 0 => 0.0,
                _ => 1.0,
            },
            (None, None) => 1.0,
        })
        .collect()
}

/// The mesh triangle that made draw `index` of `chunk`, when the chunk
/// recorded its sources.
fn triangle_of(chunk: &PrimitiveChunk, index: u32) -> Option<u32> {
    let k = chunk.triangle_ends.iter().position(|&end| end > index)?;
    Some(chunk.first_triangle + k as u32)
}
