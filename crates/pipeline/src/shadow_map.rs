//! Shadow maps (`ShadowMode::Map`): a depth image from each light, drawn
//! with the raster core (`zline_raster`: snapped vertices, the edge table,
//! depth planes), then read per sample by the Phong kernels.
//!
//! - A directional light gets one orthographic map fitted to the scene's
//!   bounds, looking along the light; depth is the distance along it.
//! - A point light gets a cube: six 90° perspective faces, one per axis of
//!   eye space (±x, ±y, ±z); a sample reads the face of its largest
//!   coordinate seen from the light, depth is that coordinate's magnitude.
//!   Faces are drawn with 1/depth interpolated (it is affine in the face's
//!   screen) and store the nearest depth.
//! - Every triangle casts, both sides, the receiver's own included.
//!
//! A sample at depth d (from the light) is hidden when d − bias exceeds
//! the stored depth. The bias is slope-scaled: (1.5 + 2·tan θ) texels'
//! worth of depth at the sample, θ the angle between the normal and the
//! light, tan θ at most 10, times `Shadows::bias` (1 by default). With PCF the light's share is the fraction of
//! the 3 × 3 texels around the sample that see it; without, the nearest
//! texel decides.

use glam::{Mat4, Vec3};
use rayon::prelude::*;
use zline_raster::{DepthPlane, EdgeTable, FixedPoint, PlaneBasis, Rect};
use zline_scene::{Light, Scene};
use zline_shading::Vec3x8;
use zline_simd::lanes::{f32x8, Level};

use crate::shadow::Polygon;

/// The near plane of a point light's faces, as a share of the scene's size.
const NEAR: f32 = 1e-4;

/// One depth image: `size` × `size` texels, row-major.
#[derive(Clone, Debug, Default)]
struct DepthMap {
    size: u32,
    depth: Vec<f32>,
}

impl DepthMap {
    /// Empties the map and sizes it `size` × `size`, keeping its buffer.
    fn reset(&mut self, size: u32) {
        self.size = size;
        self.depth.clear();
        self.depth.resize(size as usize * size as usize, f32::INFINITY);
    }

    /// Draws a triangle given in map texel coordinates (x, y) with the value
    /// `v` per vertex interpolated affinely; stores `depth(v)` where it is
    /// nearer than what is there.
    fn draw(&mut self, p: [(f32, f32); 3], v: [f64; 3], depth: impl Fn(f64) -> f32) {
        let snap = |k: usize| FixedPoint::snap(p[k].0, p[k].1);
        let (Some(a), Some(b), Some(c)) = (snap(0), snap(1), snap(2)) else {
            return;
        };
        let fixed = [a, b, c];
        let (Some(edges), Some(basis)) = (EdgeTable::new(fixed), PlaneBasis::new(fixed)) else {
            return;
        };
        let plane = DepthPlane::new(&basis, v);
        let n = self.size as i32;
        let size = self.size as usize;
        edges.scan(
            Rect { x0: 0, y0: 0, x1: n, y1: n },
            #[inline(always)]
            |s| {
                for x in s.x0..s.x1 {
                    let d = depth(plane.at(f64::from(x) + 0.5, f64::from(s.y) + 0.5));
                    let t = &mut self.depth[s.y as usize * size + x as usize];
                    if d < *t {
                        *t = d;
                    }
                }
            },
        );
    }

    /// The stored depth at texel (x, y), clamped to the map.
    #[inline(always)]
    fn at(&self, x: i32, y: i32) -> f32 {
        let last = self.size as i32 - 1;
        self.depth[y.clamp(0, last) as usize * self.size as usize + x.clamp(0, last) as usize]
    }
}

/// A light's maps, in eye space.
#[derive(Clone, Debug)]
enum LightMap {
    /// Orthographic: `from_eye` takes an eye-space point to (x, y) in
    /// texels and z the depth along the light.
    Directional { from_eye: Mat4, map: DepthMap, texel: f32, to_light: Vec3 },
    /// Six faces around the light at `position`; face 2·axis + (1 if the
    /// coordinate is negative).
    Point { position: Vec3, faces: Vec<DepthMap> },
    /// A light that casts nothing (no geometry, or a degenerate light).
    Unshadowed,
}

/// The frame's shadow maps, one entry per scene light, and the filter.
/// Kept from frame to frame ([`ShadowMaps::rebuild`]): the maps' buffers
/// and the scratch of triangles are reused.
#[derive(Clone, Debug, Default)]
pub struct ShadowMaps {
    lights: Vec<LightMap>,
    pcf: bool,
    /// The scale on the slope-scaled bias (`Shadows::bias`).
    bias: f32,
    /// Scratch: every triangle of the scene in eye space.
    tris: Vec<[Vec3; 3]>,
    /// Scratch: one object's vertices in eye space.
    positions: Vec<Vec3>,
}

/// The two axes that span a cube face of `axis` (texel x, texel y).
fn face_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    }
}

impl ShadowMaps {
    /// Draws the maps of every light of `scene` with `eye_from_world` as
    /// the frame's view.
    pub fn build(scene: &Scene, eye_from_world: &Mat4) -> ShadowMaps {
        let mut maps = ShadowMaps::default();
        maps.rebuild(scene, eye_from_world);
        maps
    }

    /// [`Self::build`] into these maps, reusing their buffers: a steady
    /// stream of frames of one scene allocates nothing here.
    pub fn rebuild(&mut self, scene: &Scene, eye_from_world: &Mat4) {
        let size = scene.shadows.map_size.clamp(16, zline_scene::MAX_SHADOW_MAP_SIZE);
        // Every triangle of the scene in eye space.
        let (tris, p) = (&mut self.tris, &mut self.positions);
        tris.clear();
        for o in &scene.objects {
            let m = *eye_from_world * o.world_from_object;
            p.clear();
            p.extend(o.mesh.positions.iter().map(
                #[inline(always)]
                |&p| m.transform_point3(p),
            ));
            for t in &o.mesh.triangles {
                let v = t.map(
                    #[inline(always)]
                    |i| p.get(i as usize).copied().unwrap_or(Vec3::NAN),
                );
                if v.iter().all(
                    #[inline(always)]
                    |p| p.is_finite(),
                ) {
                    tris.push(v);
                }
            }
        }
        let (lo, hi) = tris.iter().flatten().fold(
            (Vec3::INFINITY, Vec3::NEG_INFINITY),
            #[inline(always)]
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let extent = (hi - lo).max_element();
        // Lights, and a point light's faces, are drawn in parallel: each
        // map is its own, so the result does not depend on the threads.
        let tris = &*tris;
        self.lights.truncate(scene.lights.len());
        self.lights.resize_with(scene.lights.len(), || LightMap::Unshadowed);
        self.lights.par_iter_mut().zip(&scene.lights).for_each(
            #[inline(always)]
            |(slot, light)| {
                if tris.is_empty() || !(extent.is_finite() && extent > 0.0) {
                    *slot = LightMap::Unshadowed;
                    return;
                }
                match light.transformed(eye_from_world) {
                    Light::Directional { direction, .. } => {
                        directional(tris, (lo, hi), direction, size, slot)
                    }
                    // A spot light's map is a point light's: its cone only
                    // scales what reaches the surface.
                    Light::Point { position, .. } | Light::Spot { position, .. } => {
                        point(tris, position, extent, size, slot)
                    }
                }
            },
        );
        self.bias = if scene.shadows.bias.is_finite() { scene.shadows.bias.max(0.0) } else { 1.0 };
        self.pcf = scene.shadows.pcf;
    }

    /// The share of light `k` that reaches each lane's eye-space `point`
    /// with unit `normal`: 0 (hidden) to 1 (seen).
    #[inline(always)]
    pub fn visibility_x8<S: Level>(&self, k: u32, point: Vec3x8<S>, normal: Vec3x8<S>) -> f32x8<S> {
        let Some(map) = self.lights.get(k as usize) else {
            return f32x8::ONE;
        };
        if let LightMap::Directional { from_eye, map, texel, to_light } = map {
            // The lanes together, with the scalar path's operations in its
            // order (glam's affine transform and dot product), so every lane
            // is what `visibility` computes; only the texel reads are per lane.
            let c = from_eye.to_cols_array();
            let row = zline_simd::inlined(
                #[inline(always)]
                |r: usize| {
                    f32x8::splat(c[12 + r])
                        + (f32x8::splat(c[8 + r]) * point.z
                            + (f32x8::splat(c[4 + r]) * point.y + f32x8::splat(c[r]) * point.x))
                },
            );
            let n_dot_l = normal.x * f32x8::splat(to_light.x)
                + normal.y * f32x8::splat(to_light.y)
                + normal.z * f32x8::splat(to_light.z);
            let bias = f32x8::splat(self.bias) * slope_bias_x8(n_dot_l) * f32x8::splat(*texel);
            let (x, y, d) = (row(0).to_array(), row(1).to_array(), (row(2) - bias).to_array());
            return f32x8::from(per_lane::<S>(
                #[inline(always)]
                |i| self.lookup(map, x[i], y[i], d[i]),
            ));
        }
        let (px, py, pz) = (point.x.to_array(), point.y.to_array(), point.z.to_array());
        let (nx, ny, nz) = (normal.x.to_array(), normal.y.to_array(), normal.z.to_array());
        f32x8::from(per_lane::<S>(
            #[inline(always)]
            |i| {
                let (p, n) = (Vec3::new(px[i], py[i], pz[i]), Vec3::new(nx[i], ny[i], nz[i]));
                self.visibility(map, p, n)
            },
        ))
    }

    #[inline(always)]
    fn visibility(&self, map: &LightMap, p: Vec3, n: Vec3) -> f32 {
        match map {
            LightMap::Unshadowed => 1.0,
            LightMap::Directional { from_eye, map, texel, to_light } => {
                let q = from_eye.transform_point3(p);
                let bias = self.bias * slope_bias(n.dot(*to_light)) * texel;
                self.lookup(map, q.x, q.y, q.z - bias)
            }
            LightMap::Point { position, faces } => {
                let v = p - *position;
                let a = v.abs();
                let axis = if a.x >= a.y && a.x >= a.z {
                    0
                } else if a.y >= a.z {
                    1
                } else {
                    2
                };
                let major = a[axis];
                if major.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                    return 1.0;
                }
                let face = &faces[2 * axis + usize::from(v[axis] < 0.0)];
                let (ua, ub) = face_axes(axis);
                let s = face.size as f32;
                let (x, y) = ((v[ua] / major + 1.0) * 0.5 * s, (v[ub] / major + 1.0) * 0.5 * s);
                let to_light = (-v).normalize_or_zero();
                // A texel spans 2·d/size of depth d across the face.
                let bias = self.bias * slope_bias(n.dot(to_light)) * 2.0 * major / s;
                self.lookup(face, x, y, major - bias)
            }
        }
    }

    /// 1 when the texel at (x, y) stores a depth of at least `d` (the
    /// sample is nearest), 0 when something nearer hides it; with PCF the
    /// mean over the 3 × 3 texels around it.
    #[inline(always)]
    fn lookup(&self, map: &DepthMap, x: f32, y: f32, d: f32) -> f32 {
        let (tx, ty) = (x.floor() as i32, y.floor() as i32);
        if !self.pcf {
            return if d > map.at(tx, ty) { 0.0 } else { 1.0 };
        }
        let mut seen = 0u32;
        for dy in -1..=1 {
            for dx in -1..=1 {
                seen += u32::from(d <= map.at(tx + dx, ty + dy));
            }
        }
        seen as f32 / 9.0
    }
}

/// `lane(i)` for the eight lanes, as a job of its own at level `S`: the
/// texel reads are scalar, but their floors and conversions are single
/// instructions at the v3 level (a baseline build without SSE4.1 calls
/// libm's `floorf`, which measured 5 % of a shadow-mapped frame), and the
/// kernels that read shadow maps keep one call here instead of eight
/// inlined copies.
#[inline(always)]
fn per_lane<S: Level>(lane: impl Fn(usize) -> f32) -> [f32; 8] {
    zline_simd::vectorize_at::<S, _>(zline_simd::Call(
        #[inline(always)]
        || {
            // A loop, not `array::from_fn`: its wrapper closure stays out of line.
            let mut lanes = [0.0; 8];
            for (i, v) in lanes.iter_mut().enumerate() {
                *v = lane(i);
            }
            lanes
        },
    ))
}

/// [`slope_bias`] per lane, with the same operations.
#[inline(always)]
fn slope_bias_x8<S: Level>(n_dot_l: f32x8<S>) -> f32x8<S> {
    let c = n_dot_l.abs().max(f32x8::splat(0.0995));
    let tan = (f32x8::ONE - c * c).max(f32x8::ZERO).sqrt() / c;
    f32x8::splat(1.5) + f32x8::splat(2.0) * tan.min(f32x8::splat(10.0))
}

/// The slope-scaled bias in texels: 1.5 + 2·tan θ for cos θ = `n_dot_l`,
/// tan θ at most 10.
fn slope_bias(n_dot_l: f32) -> f32 {
    let c = n_dot_l.abs().max(0.0995);
    let tan = (1.0 - c * c).max(0.0).sqrt() / c;
    1.5 + 2.0 * tan.min(10.0)
}

/// The orthographic map of a directional light travelling along
/// `direction` (eye space) over the bounds (lo, hi), into `slot` (its
/// buffer reused).
fn directional(tris: &[[Vec3; 3]], (lo, hi): (Vec3, Vec3), direction: Vec3, size: u32, slot: &mut LightMap) {
    let forward = direction.normalize_or_zero();
    if forward == Vec3::ZERO {
        *slot = LightMap::Unshadowed;
        return;
    }
    let (right, up) = forward.any_orthonormal_pair();
    let view =
        Mat4::from_cols(right.extend(0.0), up.extend(0.0), forward.extend(0.0), glam::Vec4::W).transpose();
    let corners = (0..8).map(
        #[inline(always)]
        |i| {
            Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        },
    );
    let (a, b) = corners
        .map(
            #[inline(always)]
            |c| view.transform_point3(c),
        )
        .fold(
            (Vec3::INFINITY, Vec3::NEG_INFINITY),
            #[inline(always)]
            |(a, b), p| (a.min(p), b.max(p)),
        );
    let span = (b.x - a.x).max(b.y - a.y).max(f32::MIN_POSITIVE);
    let s = size as f32;
    // Texels: x = (v.x − a.x)/span·size; depth from the box's near side.
    let to_texels = Mat4::from_scale(Vec3::new(s / span, s / span, 1.0)) * Mat4::from_translation(-a);
    let from_eye = to_texels * view;
    let mut map = match std::mem::replace(slot, LightMap::Unshadowed) {
        LightMap::Directional { map, .. } => map,
        LightMap::Point { mut faces, .. } => faces.pop().unwrap_or_default(),
        LightMap::Unshadowed => DepthMap::default(),
    };
    map.reset(size);
    for t in tris {
        let q = t.map(
            #[inline(always)]
            |p| from_eye.transform_point3(p),
        );
        map.draw(
            q.map(
                #[inline(always)]
                |q| (q.x, q.y),
            ),
            q.map(
                #[inline(always)]
                |q| f64::from(q.z),
            ),
            #[inline(always)]
            |d| d as f32,
        );
    }
    *slot = LightMap::Directional { from_eye, map, texel: span / s, to_light: -forward };
}

/// The six faces of a point light at `position` (eye space), into `slot`
/// (its buffers reused).
fn point(tris: &[[Vec3; 3]], position: Vec3, extent: f32, size: u32, slot: &mut LightMap) {
    let near = NEAR * extent;
    let s = size as f32;
    let mut faces = match std::mem::replace(slot, LightMap::Unshadowed) {
        LightMap::Point { faces, .. } => faces,
        LightMap::Directional { map, .. } => vec![map],
        LightMap::Unshadowed => Vec::new(),
    };
    faces.resize_with(6, DepthMap::default);
    faces.par_iter_mut().enumerate().for_each(
        #[inline(always)]
        |(face, map)| {
            let (axis, sign) = (face / 2, if face % 2 == 0 { 1.0 } else { -1.0 });
            let (ua, ub) = face_axes(axis);
            map.reset(size);
            for t in tris {
                // Face space: (a, b, depth) with depth along the face's axis.
                let q = t.map(
                    #[inline(always)]
                    |p| {
                        let v = p - position;
                        Vec3::new(v[ua], v[ub], sign * v[axis])
                    },
                );
                clip_near(
                    q,
                    near,
                    #[inline(always)]
                    |piece| {
                        let tex = piece.map(
                            #[inline(always)]
                            |q| ((q.x / q.z + 1.0) * 0.5 * s, (q.y / q.z + 1.0) * 0.5 * s),
                        );
                        map.draw(
                            tex,
                            piece.map(
                                #[inline(always)]
                                |q| 1.0 / f64::from(q.z),
                            ),
                            #[inline(always)]
                            |inv| (1.0 / inv) as f32,
                        );
                    },
                );
            }
        },
    );
    *slot = LightMap::Point { position, faces };
}

/// The parts of triangle `q` (face space) with depth ≥ `near`, as a fan
/// of at most two triangles handed to `piece` (clipped on the stack with
/// the planar shadows' [`Polygon`], in f64).
fn clip_near(q: [Vec3; 3], near: f32, mut piece: impl FnMut([Vec3; 3])) {
    let [a, b, c] = q.map(
        #[inline(always)]
        |p| p.as_dvec3(),
    );
    let mut poly = Polygon::triangle(a, b, c).clip(
        #[inline(always)]
        |x| x.z - f64::from(near),
    );
    let points = poly.points_mut();
    for k in 1..points.len().saturating_sub(1) {
        piece([points[0], points[k], points[k + 1]].map(
            #[inline(always)]
            |p| p.as_vec3(),
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use zline_simd::lanes::Baseline;

    #[test]
    fn a_drawn_triangle_keeps_the_nearest_depth() {
        let mut m = DepthMap::default();
        m.reset(16);
        m.draw([(0.0, 0.0), (16.0, 0.0), (0.0, 16.0)], [5.0; 3], |d| d as f32);
        m.draw([(0.0, 0.0), (16.0, 0.0), (0.0, 16.0)], [7.0; 3], |d| d as f32);
        assert_eq!(m.at(2, 2), 5.0);
        assert_eq!(m.at(15, 15), f32::INFINITY, "outside the triangle");
    }

    #[test]
    fn the_bias_grows_with_the_slope() {
        assert_eq!(slope_bias(1.0), 1.5);
        assert!(slope_bias(0.5) > slope_bias(0.9));
        assert!(slope_bias(0.0) <= 21.5 + 1e-3);
    }

    #[test]
    fn eight_lanes_give_each_lane_s_visibility() {
        use std::sync::Arc;
        use zline_scene::{Camera, Object, Projection, RenderSettings, Shadows};
        let object = |mesh, m: Mat4| Object {
            mesh: Arc::new(mesh),
            world_from_object: m,
            material: None,
            shading: None,
            cull_back_faces: false,
        };
        let mut scene = Scene {
            environment: None,
            camera: Camera {
                eye: Vec3::new(0.0, 3.0, 4.0),
                target: Vec3::ZERO,
                up: Vec3::Y,
                projection: Projection::Perspective { fovy_degrees: 45.0, near: 0.5, far: 20.0 },
            },
            background: Vec3::ZERO,
            ambient: Vec3::ZERO,
            lights: vec![
                Light::Directional { direction: Vec3::new(0.4, -1.0, 0.3), color: Vec3::ONE },
                Light::Point {
                    position: Vec3::new(0.5, 2.0, 0.2),
                    color: Vec3::ONE,
                    attenuation: Default::default(),
                },
            ],
            objects: vec![
                object(zline_scene::plane(6.0, 4), Mat4::IDENTITY),
                object(zline_scene::cube(1.0), Mat4::from_translation(Vec3::new(0.0, 0.7, 0.0))),
            ],
            settings: RenderSettings::default(),
            fog: None,
            shadows: Shadows { map_size: 64, ..Shadows::default() },
        };
        let view = scene.camera.eye_from_world();
        for pcf in [true, false] {
            scene.shadows.pcf = pcf;
            let maps = ShadowMaps::build(&scene, &view);
            for seed in 0..64u32 {
                let f = |i: u32| ((seed * 8 + i) as f32 * 0.618_034).fract() * 4.0 - 2.0;
                let points: [Vec3; 8] = std::array::from_fn(|i| {
                    view.transform_point3(Vec3::new(f(i as u32), 0.05 * f(i as u32 + 3), f(i as u32 + 5)))
                });
                let normals: [Vec3; 8] = std::array::from_fn(|i| {
                    view.transform_vector3(
                        Vec3::new(0.1 * f(i as u32 + 1), 1.0, 0.1 * f(i as u32 + 2)).normalize(),
                    )
                });
                let lanes = |v: &[Vec3; 8]| Vec3x8::<Baseline> {
                    x: f32x8::from(v.map(|p| p.x)),
                    y: f32x8::from(v.map(|p| p.y)),
                    z: f32x8::from(v.map(|p| p.z)),
                };
                for k in 0..2 {
                    let got = maps.visibility_x8(k, lanes(&points), lanes(&normals)).to_array();
                    for i in 0..8 {
                        let want = maps.visibility(&maps.lights[k as usize], points[i], normals[i]);
                        assert_eq!(got[i].to_bits(), want.to_bits(), "pcf {pcf}, light {k}, lane {i}");
                    }
                }
            }
        }
    }

    #[test]
    fn near_clipping_keeps_the_far_part() {
        let q = [Vec3::new(0.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, 1.0, 1.0)];
        let mut pieces = Vec::new();
        clip_near(q, 0.5, |t| pieces.push(t));
        assert_eq!(pieces.len(), 2);
        assert!(pieces.iter().flatten().all(|p| p.z >= 0.5 - 1e-6));
        clip_near([Vec3::NEG_Z; 3], 0.1, |t| panic!("{t:?} lies behind the near plane"));
    }
}
