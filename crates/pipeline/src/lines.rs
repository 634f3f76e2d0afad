//! Lines: the mesh edges of a frame (`RenderSettings::wireframe`) as
//! clipped window-space segments, binned per tile. `tile::lines` draws
//! them into each tile after its surfaces, before the resolve.
//!
//! **Edges.** Each undirected edge once per object: vertices are welded by
//! position (bit-equal coordinates, −0 = +0), so the split vertices of a
//! hard edge or a texture seam do not double it. With a feature angle only
//! feature edges are kept: border edges (one face) and non-manifold ones
//! (three or more) always, silhouettes (of two faces, one towards the
//! viewer and one away) and creases (face normals more than the angle
//! apart). A degenerate face's edges are kept.
//!
//! **Clipping.** Each edge is clipped in f64 clip space to the view volume
//! (−w ≤ x, y, z ≤ w, SPEC §1) before any divide, as triangles are: a
//! segment with an end behind the camera is cut at the near plane, never
//! divided by w ≤ 0. Non-finite ends draw nothing.
//!
//! **Rasterization** (`tile::lines`): 1 pixel wide, not anti-aliased, a
//! DDA over pixel centres along the major axis: for a segment with
//! |Δx| ≥ |Δy|, every column i whose centre i + ½ lies in [min x, max x)
//! gets the pixel of row ⌊y(i + ½)⌋ (rows and columns swapped for
//! |Δy| > |Δx|), evaluated in f64 from the segment's ends. The pixel
//! depends only on the segment, never on the tile, so any tile size gives
//! the same lines. With supersampling, all n × n samples of that pixel are
//! drawn (each tested against its own depth), so a line stays 1 pixel wide.
//!
//! **Visibility.** The line's depth (in the frame's depth encoding, which
//! is affine in window space, so interpolated linearly along the segment)
//! at the pixel's point on the line is compared with each sample's stored
//! depth: the sample shows the line as visible when
//! `z_line ≤ z_stored + DEPTH_EPSILON + min(1 px · s, SLOPE_CAP · D)`,
//! where s = |∂z/∂x| + |∂z/∂y| (per pixel) is the steepest window-space
//! depth slope of the edge's faces that face the viewer (of all its faces
//! when none does; non-finite slopes of faces with a vertex behind the
//! camera or edge-on count as 0) and D the object's depth extent (over its
//! vertices in front of the camera). The slope term covers the distance
//! from the exact edge to the sample (under ½ pixel across, under 1 pixel
//! with supersampling) on a face beside it; the cap keeps the nearly
//! edge-on faces beside a silhouette from letting everything behind them
//! through (a silhouette pixel on such a face may then read as hidden);
//! `DEPTH_EPSILON` covers rounding. A surface nearer than the tolerance
//! does not hide a line.
//!
//! **Dashes** (hidden-dashed): a hidden pixel is drawn when its column
//! (row, for a mostly vertical segment) modulo [`DASH_PERIOD`] is below
//! [`DASH_ON`]: 6 pixels on, 4 off, measured along the major axis in
//! window pixels (6 to 8.5 pixels along the line). The pattern is fixed to
//! the window, not to each edge, so a chain of short edges (a silhouette
//! of a fine mesh, edges of 2–3 pixels) is dashed as one line.

use glam::{DVec3, DVec4, Vec3};
use rayon::prelude::*;
use zline_scene::{Mesh, WireframeMode};

use crate::bin::TileGrid;
use crate::setup::DepthEncoding;
use crate::vertex::ObjectTransforms;

/// Depth tolerance of the visibility test, in stored depth units.
pub const DEPTH_EPSILON: f64 = 1.0 / 65536.0;

/// Length of a dash, in pixels along the major axis.
pub const DASH_ON: i32 = 6;

/// Length of a dash and the gap after it, in pixels along the major axis.
pub const DASH_PERIOD: i32 = 10;

/// The slope term of the tolerance is at most this share of the object's
/// depth extent (the faces beside a silhouette are nearly edge-on, with
/// slopes that would let everything behind them through).
pub const SLOPE_CAP: f64 = 1.0 / 64.0;

/// One clipped edge in window pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Start (x, y) in pixels.
    pub a: [f64; 2],
    /// End (x, y) in pixels.
    pub b: [f64; 2],
    /// Stored-depth value at the start and the end.
    pub z: [f64; 2],
    /// How far in front of the line a stored depth must be to hide it.
    pub tolerance: f64,
}

/// What the line stage needs of the frame.
#[derive(Clone, Copy, Debug)]
pub struct LineFrame {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// How depth is stored.
    pub depth: DepthEncoding,
    /// Perspective (viewer at the eye-space origin) or orthographic
    /// (viewer along +z).
    pub perspective: bool,
}

/// A face as the edge filter reads it.
#[derive(Clone, Copy, Debug)]
struct Face {
    /// Unnormalized object-space normal (counter-clockwise winding).
    normal: DVec3,
    /// Faces the viewer.
    front: bool,
    /// |∂z/∂x| + |∂z/∂y| in window pixels (0 when not finite).
    slope: f64,
}

/// The frame's segments and their bins, kept from frame to frame.
#[derive(Debug, Default)]
pub struct Lines {
    /// The segments, objects in order, edges by welded vertex index.
    pub segments: Vec<Segment>,
    /// Per tile (row-major), the segments whose bounds touch it, in order.
    bins: Vec<Vec<u32>>,
    /// The mode.
    pub mode: WireframeMode,
    /// The line colour: black on a light background, white on a dark one.
    pub color: Vec3,
    order: Vec<u32>,
    weld: Vec<u32>,
    clip: Vec<DVec4>,
    faces: Vec<Face>,
    edges: Vec<(u32, u32, u32)>,
    /// The radix sort's second buffer for `edges`.
    sorted: Vec<(u32, u32, u32)>,
    /// Where each edge's run of faces starts in `edges`, and the end.
    runs: Vec<u32>,
    /// Each run's segment, if it has one.
    found: Vec<Option<Segment>>,
    /// Each segment's tiles: columns x0..=x1, rows y0..=y1.
    ranges: Vec<[u32; 4]>,
}

/// An edge slot without an edge: after every real (a, b, face) key.
const NO_EDGE: (u32, u32, u32) = (u32::MAX, u32::MAX, u32::MAX);

/// The most threads at which the edges are radix-sorted ([`radix_sort`],
/// on one thread): its passes are fewer operations than a comparison
/// sort's (the 69k bunny's line geometry 27 → 19 ms at one thread, 14 → 12
/// at two), but on a lent 16-core machine a serial radix sort (a crate's,
/// which allocated its buffer at each call) made that geometry at 16
/// threads 8.5 → 15–18 ms, worse from 4 threads on. Both sorts give the
/// same order.
const RADIX_THREADS: usize = 2;

impl Lines {
    /// Empties the set for a frame drawn with `mode` on `background`.
    pub fn reset(&mut self, mode: WireframeMode, background: Vec3) {
        self.segments.clear();
        self.mode = mode;
        let luminance = 0.2126 * background.x + 0.7152 * background.y + 0.0722 * background.z;
        self.color = if luminance > 0.5 { Vec3::ZERO } else { Vec3::ONE };
    }

    /// Appends the edges of one object (see the module's rules).
    pub fn add_object(
        &mut self,
        mesh: &Mesh,
        transforms: &ObjectTransforms,
        frame: &LineFrame,
        feature_angle: Option<f32>,
    ) {
        let positions = &mesh.positions;
        self.weld_vertices(positions);
        let m = transforms.clip_from_object.as_dmat4();
        positions.par_iter().map(|p| m * p.as_dvec3().extend(1.0)).collect_into_vec(&mut self.clip);
        let object_from_eye = transforms.eye_from_object.as_dmat4().inverse();
        let viewer = if frame.perspective {
            object_from_eye * DVec4::new(0.0, 0.0, 0.0, 1.0)
        } else {
            object_from_eye * DVec4::new(0.0, 0.0, 1.0, 0.0)
        };
        // Per triangle, in parallel: its face, and its three edges in its
        // own three slots; a degenerate edge (or every edge of a triangle
        // with an index out of range, a hand-built mesh) is a sentinel that
        // sorts after every real key and is cut off.
        let (clip, weld) = (&self.clip, &self.weld);
        self.edges.resize(mesh.triangles.len() * 3, NO_EDGE);
        let triangles = mesh.triangles.par_iter().zip(self.edges.par_chunks_mut(3)).enumerate();
        let faces = triangles.map(|(f, (t, edges))| {
            edges.fill(NO_EDGE);
            let corner = |k: usize| positions.get(t[k] as usize).map(|p| p.as_dvec3());
            let (Some(p0), Some(p1), Some(p2)) = (corner(0), corner(1), corner(2)) else {
                return Face { normal: DVec3::ZERO, front: false, slope: 0.0 };
            };
            let normal = (p1 - p0).cross(p2 - p0);
            let towards = if frame.perspective { viewer.truncate() - p0 } else { viewer.truncate() };
            for (k, edge) in edges.iter_mut().enumerate() {
                let (a, b) = (weld[t[k] as usize], weld[t[(k + 1) % 3] as usize]);
                if a != b {
                    *edge = (a.min(b), a.max(b), f as u32);
                }
            }
            let clip = t.map(|i| clip[i as usize]);
            Face { normal, front: normal.dot(towards) > 0.0, slope: slope(clip, frame) }
        });
        faces.collect_into_vec(&mut self.faces);
        // Sorted by (pair, face), the one order for any thread count: on a
        // pool of at most RADIX_THREADS threads by a stable radix sort of the
        // pair (the edges are in face order), the sentinels first taken
        // out; on more by the parallel comparison sort.
        if rayon::current_num_threads() <= RADIX_THREADS {
            self.edges.retain(|e| e.0 != NO_EDGE.0);
            radix_sort(&mut self.edges, &mut self.sorted, |&(a, b, _)| (u64::from(a) << 32) | u64::from(b));
        } else {
            // Every key is distinct (it holds the face): one order.
            self.edges.par_sort_unstable();
            self.edges.truncate(self.edges.partition_point(|e| e.0 != NO_EDGE.0));
        }
        // The runs of one edge (its faces), then each run's segment in
        // parallel, in order.
        self.runs.clear();
        let mut start = 0;
        while start < self.edges.len() {
            self.runs.push(start as u32);
            let key = (self.edges[start].0, self.edges[start].1);
            start += self.edges[start..].iter().take_while(|e| (e.0, e.1) == key).count();
        }
        self.runs.push(self.edges.len() as u32);
        let cap = depth_extent(&self.clip, frame) * SLOPE_CAP;
        let cos_limit = feature_angle.map(|a| f64::from(a).to_radians().cos());
        let (edges, faces, clip) = (&self.edges, &self.faces, &self.clip);
        let found = self.runs.par_windows(2).map(|run| {
            let run = &edges[run[0] as usize..run[1] as usize];
            let (a, b, _) = run[0];
            let faces = run.iter().map(|e| faces[e.2 as usize]);
            if cos_limit.is_some_and(|limit| !feature(faces.clone(), limit)) {
                return None;
            }
            let front = faces.clone().filter(|f| f.front).map(|f| f.slope).fold(None, max);
            let s = front.or_else(|| faces.map(|f| f.slope).fold(None, max)).unwrap_or(0.0);
            segment(clip[a as usize], clip[b as usize], frame, DEPTH_EPSILON + s.min(cap))
        });
        found.collect_into_vec(&mut self.found);
        self.segments.extend(self.found.iter().flatten());
    }

    /// `weld[v]`: the smallest index of a vertex at `v`'s position.
    fn weld_vertices(&mut self, positions: &[Vec3]) {
        let key = |p: Vec3| [(p.x + 0.0).to_bits(), (p.y + 0.0).to_bits(), (p.z + 0.0).to_bits()];
        self.order.clear();
        self.order.extend(0..positions.len() as u32);
        self.order.par_sort_unstable_by_key(|&i| (key(positions[i as usize]), i));
        self.weld.clear();
        self.weld.resize(positions.len(), 0);
        let mut first = 0;
        for (k, &i) in self.order.iter().enumerate() {
            if k == 0 || key(positions[i as usize]) != key(positions[self.order[k - 1] as usize]) {
                first = i;
            }
            self.weld[i as usize] = first;
        }
    }

    /// Lists each segment in the tiles (of `grid`, in samples, `n` per
    /// pixel side) its pixel bounds touch.
    pub fn bin(&mut self, grid: &TileGrid, n: u32) {
        self.bins.resize_with(grid.len(), Vec::new);
        self.bins.truncate(grid.len());
        self.bins.iter_mut().for_each(Vec::clear);
        if grid.is_empty() {
            return;
        }
        let (ts, n) = (f64::from(grid.tile_size), f64::from(n));
        let (cols, rows) = (grid.cols as usize, grid.rows as usize);
        // In bands of tile rows, one task a band (as `bin::bin_primitives`
        // does): each scans every segment and fills its own tiles' lists,
        // in segment order whatever the band count.
        let rows_per_band = crate::bin::rows_per_band(grid);
        // Each segment's tile range once, in parallel; the bands then scan
        // the ranges.
        let tile = |v: f64, count: usize| ((v.floor() * n / ts).max(0.0) as usize).min(count - 1) as u32;
        let ranges = self.segments.par_iter().map(|s| {
            let (x0, x1) = (tile(s.a[0].min(s.b[0]), cols), tile(s.a[0].max(s.b[0]), cols));
            let (y0, y1) = (tile(s.a[1].min(s.b[1]), rows), tile(s.a[1].max(s.b[1]), rows));
            [x0, x1, y0, y1]
        });
        ranges.collect_into_vec(&mut self.ranges);
        let ranges = &self.ranges;
        self.bins.par_chunks_mut(rows_per_band * cols).enumerate().for_each(|(band, bins)| {
            let first = band * rows_per_band;
            let last = first + bins.len() / cols - 1;
            for (k, range) in ranges.iter().enumerate() {
                let [x0, x1, y0, y1] = range.map(|v| v as usize);
                if y1 < first || y0 > last {
                    continue;
                }
                for row in y0.max(first)..=y1.min(last) {
                    for col in x0..=x1 {
                        bins[(row - first) * cols + col].push(k as u32);
                    }
                }
            }
        });
    }

    /// The segments binned in tile `tile` (empty before [`Lines::bin`]).
    pub fn bin_of(&self, tile: usize) -> &[u32] {
        self.bins.get(tile).map_or(&[], Vec::as_slice)
    }
}

/// Sorts `items` by `key`, stably: a least-significant-digit radix sort by
/// bytes, `scratch` its second buffer (kept from frame to frame, so a steady
/// frame allocates nothing). One pass counts every byte's values, then one
/// pass a byte that is not the same in every key.
fn radix_sort<T: Copy>(items: &mut Vec<T>, scratch: &mut Vec<T>, key: impl Fn(&T) -> u64) {
    let n = items.len();
    let mut counts = [[0usize; 256]; 8];
    for item in items.iter() {
        let k = key(item);
        for (byte, count) in counts.iter_mut().enumerate() {
            count[(k >> (8 * byte)) as u8 as usize] += 1;
        }
    }
    for (byte, count) in counts.iter().enumerate() {
        if count.contains(&n) {
            continue;
        }
        let mut next = [0usize; 256];
        let mut sum = 0;
        for (next, &c) in next.iter_mut().zip(count) {
            (*next, sum) = (sum, sum + c);
        }
        scratch.clear();
        scratch.resize(n, items[0]);
        for item in items.iter() {
            let slot = &mut next[(key(item) >> (8 * byte)) as u8 as usize];
            scratch[*slot] = *item;
            *slot += 1;
        }
        std::mem::swap(items, scratch);
    }
}

fn max(a: Option<f64>, b: f64) -> Option<f64> {
    Some(a.map_or(b, |a| a.max(b)))
}

/// True for a feature edge: a border or non-manifold edge, a silhouette, a
/// crease sharper than `cos_limit`, or an edge of a degenerate face.
fn feature(mut faces: impl Iterator<Item = Face>, cos_limit: f64) -> bool {
    let (Some(f), Some(g), None) = (faces.next(), faces.next(), faces.next()) else {
        return true;
    };
    let lengths = f.normal.length() * g.normal.length();
    let usable = lengths.is_finite() && lengths > 0.0;
    if !usable {
        return true;
    }
    f.front != g.front || f.normal.dot(g.normal) / lengths < cos_limit
}

/// The range of stored depth over the vertices in front of the camera.
fn depth_extent(clip: &[DVec4], frame: &LineFrame) -> f64 {
    let depths = clip.iter().filter(|c| c.w > 0.0).map(|&c| window(c, frame).z).filter(|z| z.is_finite());
    let (lo, hi) = depths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| (lo.min(z), hi.max(z)));
    if hi >= lo {
        hi - lo
    } else {
        0.0
    }
}

/// The window-space depth slope of a face, |∂z/∂x| + |∂z/∂y| per pixel;
/// 0 when a vertex has w ≤ 0 or the face is edge-on.
fn slope(clip: [DVec4; 3], frame: &LineFrame) -> f64 {
    let p = clip.map(|c| window(c, frame));
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let det = e1.x * e2.y - e2.x * e1.y;
    let dzdx = (e1.z * e2.y - e2.z * e1.y) / det;
    let dzdy = (e1.x * e2.z - e2.x * e1.z) / det;
    let s = dzdx.abs() + dzdy.abs();
    if clip.iter().all(|c| c.w > 0.0) && s.is_finite() {
        s
    } else {
        0.0
    }
}

/// Window x, y in pixels and the stored depth of a clip-space point.
fn window(c: DVec4, frame: &LineFrame) -> DVec3 {
    let (x, y, z) = (c.x / c.w, c.y / c.w, c.z / c.w);
    let depth = match frame.depth {
        DepthEncoding::Normalized => z,
        DepthEncoding::Reversed { .. } => (z - 1.0) / 2.0,
    };
    DVec3::new((x + 1.0) * 0.5 * f64::from(frame.width), (1.0 - y) * 0.5 * f64::from(frame.height), depth)
}

/// The edge from `a` to `b` (clip space) clipped to the view volume and
/// mapped to the window; `None` when nothing of it is inside or an end is
/// not finite.
pub fn segment(a: DVec4, b: DVec4, frame: &LineFrame, tolerance: f64) -> Option<Segment> {
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    let (t0, t1) = clip_range(a, b)?;
    let (p, q) = (a.lerp(b, t0), a.lerp(b, t1));
    let in_front = p.w > 0.0 && q.w > 0.0;
    if !in_front {
        return None;
    }
    let (p, q) = (window(p, frame), window(q, frame));
    Some(Segment { a: [p.x, p.y], b: [q.x, q.y], z: [p.z, q.z], tolerance })
}

/// The parameter range [t0, t1] ⊆ [0, 1] of a + t(b − a) inside
/// −w ≤ x, y, z ≤ w (Liang–Barsky), or `None`.
fn clip_range(a: DVec4, b: DVec4) -> Option<(f64, f64)> {
    let distances = |v: DVec4| [v.w + v.x, v.w - v.x, v.w + v.y, v.w - v.y, v.w + v.z, v.w - v.z];
    let (da, db) = (distances(a), distances(b));
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (&d0, &d1) in da.iter().zip(&db) {
        if d0 < 0.0 && d1 < 0.0 {
            return None;
        }
        if d0 < 0.0 {
            t0 = t0.max(d0 / (d0 - d1));
        } else if d1 < 0.0 {
            t1 = t1.min(d0 / (d0 - d1));
        }
    }
    (t0 <= t1).then_some((t0, t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    const FRAME: LineFrame =
        LineFrame { width: 100, height: 50, depth: DepthEncoding::Normalized, perspective: true };

    #[test]
    fn a_segment_inside_maps_to_the_window() {
        let s =
            segment(DVec4::new(-1.0, 1.0, 0.0, 1.0), DVec4::new(0.5, -0.5, 0.5, 2.0), &FRAME, 0.0).unwrap();
        assert_eq!(s.a, [0.0, 0.0]);
        assert_eq!(s.b, [62.5, 31.25]);
        assert_eq!(s.z, [0.0, 0.25]);
    }

    #[test]
    fn an_end_behind_the_camera_is_cut_at_the_near_plane() {
        // w = 1 in front, w = -1 behind, z = -w at t where z + w = 0.
        let (a, b) = (DVec4::new(0.0, 0.0, 0.0, 1.0), DVec4::new(0.0, 0.0, -3.0, -1.0));
        let s = segment(a, b, &FRAME, 0.0).unwrap();
        // z + w: 1 at a, -4 at b: t = 0.2, point (0, 0, -0.6, 0.6): NC z -1.
        assert_eq!(s.z[1], -1.0);
        assert!(s.b.iter().chain(&s.a).all(|v| v.is_finite()));
        // Both ends behind: nothing.
        assert!(segment(DVec4::new(0.0, 0.0, 1.0, -1.0), b, &FRAME, 0.0).is_none());
        // Through w = 0 exactly, and non-finite ends: nothing, no panic.
        assert!(segment(DVec4::ZERO, DVec4::ZERO, &FRAME, 0.0).is_none());
        assert!(segment(DVec4::splat(f64::NAN), a, &FRAME, 0.0).is_none());
        assert!(segment(DVec4::new(f64::INFINITY, 0.0, 0.0, 1.0), a, &FRAME, 0.0).is_none());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        /// The clipped range against brute force: points of the segment
        /// sampled along it are inside the view volume exactly within
        /// [t0, t1] (away from its ends by 1e-6).
        #[test]
        fn the_clipped_range_is_where_the_segment_is_inside(
            a in proptest::array::uniform4(-3.0f64..3.0),
            b in proptest::array::uniform4(-3.0f64..3.0),
        ) {
            let (a, b) = (DVec4::from_array(a), DVec4::from_array(b));
            let inside = |v: DVec4| v.x.abs() <= v.w && v.y.abs() <= v.w && v.z.abs() <= v.w;
            let range = clip_range(a, b);
            for k in 0..=200 {
                let t = f64::from(k) / 200.0;
                let expected = inside(a.lerp(b, t));
                match range {
                    Some((t0, t1)) if t > t0 + 1e-6 && t < t1 - 1e-6 => proptest::prop_assert!(expected, "t {t} in [{t0}, {t1}]"),
                    Some((t0, t1)) if t < t0 - 1e-6 || t > t1 + 1e-6 => proptest::prop_assert!(!expected, "t {t} outside [{t0}, {t1}]"),
                    None => proptest::prop_assert!(!expected, "t {t}: no range, but inside"),
                    Some(_) => {}
                }
            }
        }
    }

    proptest::proptest! {
        /// The radix sort is the standard library's stable sort by the same
        /// key: keys of few and of many distinct bytes, and repeats.
        #[test]
        fn the_radix_sort_is_a_stable_sort(
            keys in proptest::collection::vec((0u64..4, proptest::num::u64::ANY), 0..300),
            wide in proptest::bool::ANY,
        ) {
            let items: Vec<(u64, usize)> = keys.iter().enumerate().map(|(i, &(small, any))| (if wide { any } else { small << 40 }, i)).collect();
            let mut expected = items.clone();
            expected.sort_by_key(|item| item.0);
            let (mut sorted, mut scratch) = (items, Vec::new());
            radix_sort(&mut sorted, &mut scratch, |item| item.0);
            proptest::prop_assert_eq!(sorted, expected);
        }
    }

    /// The radix sort (one and two threads) and the parallel sort (more)
    /// give the same welds and segments, in the same order, on a triangle
    /// soup (every corner its own vertex, welded by position; every edge
    /// shared by two faces).
    #[test]
    fn the_sorts_give_one_order_at_any_thread_count() {
        let welded = zline_scene::uv_sphere(24, 48, 1.0);
        let positions: Vec<Vec3> = (0..welded.triangle_count()).flat_map(|t| welded.triangle(t)).collect();
        let triangles = (0..welded.triangle_count() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        let sphere = Mesh::new("soup", positions, None, triangles, welded.material).unwrap();
        let transforms = ObjectTransforms::new(
            glam::Mat4::perspective_rh_gl(1.0, 2.0, 0.1, 100.0),
            glam::Mat4::look_at_rh(Vec3::new(0.3, 0.4, 3.0), Vec3::ZERO, Vec3::Y),
            glam::Mat4::IDENTITY,
        );
        let draw = |threads: usize, feature: Option<f32>| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut lines = Lines::default();
            lines.reset(WireframeMode::All, Vec3::ONE);
            pool.install(|| lines.add_object(&sphere, &transforms, &FRAME, feature));
            (lines.weld, lines.segments)
        };
        for feature in [None, Some(5.0)] {
            let one = draw(1, feature);
            assert!(one.0.iter().enumerate().any(|(v, &w)| w as usize != v), "no vertex was welded");
            assert!(!one.1.is_empty());
            for threads in [2, 3, 8] {
                assert!(draw(threads, feature) == one, "{threads} threads, feature angle {feature:?}");
            }
        }
    }

    #[test]
    fn a_cube_has_twelve_feature_edges_and_eighteen_edges() {
        let cube = zline_scene::cube(1.0);
        let transforms = ObjectTransforms::new(
            glam::Mat4::perspective_rh_gl(1.0, 2.0, 0.1, 100.0),
            glam::Mat4::look_at_rh(Vec3::new(3.0, 2.5, 2.0), Vec3::ZERO, Vec3::Y),
            glam::Mat4::IDENTITY,
        );
        let mut lines = Lines::default();
        lines.reset(WireframeMode::All, Vec3::ONE);
        lines.add_object(&cube, &transforms, &FRAME, Some(30.0));
        assert_eq!(lines.segments.len(), 12);
        lines.reset(WireframeMode::All, Vec3::ONE);
        lines.add_object(&cube, &transforms, &FRAME, None);
        assert_eq!(lines.segments.len(), 18, "12 edges and 6 face diagonals, each once");
        assert_eq!(lines.color, Vec3::ZERO);
    }
}
