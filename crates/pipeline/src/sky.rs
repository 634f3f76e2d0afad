//! The environment drawn as the background (`Environment::background`,
//! SPEC §5.3): each undrawn sample takes the panorama's radiance along the
//! ray through its centre, instead of the background colour. A tile that
//! shows the sky computes it once per sample when it is cleared, into
//! planes the resolve and the blending passes read like the colour planes.

use glam::{Mat4, Vec3, Vec4};
use zline_raster::LANES;
use zline_shading::Environment;
use zline_simd::lanes::f32x8;

use crate::setup::Viewer;
use crate::tile::TileTarget;

/// What a tile needs to find the radiance behind each of its samples.
#[derive(Clone, Debug)]
pub(crate) struct SkyView {
    /// The environment in eye space.
    environment: Environment,
    eye_from_clip: Mat4,
    viewer: Viewer,
    /// The viewport in samples.
    size: (f32, f32),
    /// The largest value a sample keeps, as a lit colour's
    /// (`PreparedLights::ceiling`): a sun does not whiten a supersampled
    /// pixel unless a tone mapping follows.
    ceiling: f32,
}

impl SkyView {
    /// The sky of `environment` (world space) seen through a camera with
    /// these matrices, over a viewport of `width × height` samples.
    pub(crate) fn new(
        environment: &Environment,
        (eye_from_world, clip_from_eye): (Mat4, Mat4),
        viewer: Viewer,
        (width, height, ceiling): (u32, u32, f32),
    ) -> SkyView {
        SkyView {
            environment: environment.transformed(&eye_from_world),
            eye_from_clip: clip_from_eye.inverse(),
            viewer,
            size: (width as f32, height as f32),
            ceiling,
        }
    }

    /// The unit eye-space direction of the ray through the centre of
    /// sample (`x`, `y`).
    pub(crate) fn direction(&self, x: i32, y: i32) -> Vec3 {
        if self.viewer == Viewer::AlongMinusZ {
            return Vec3::NEG_Z;
        }
        let ndc_x = (x as f32 + 0.5) / self.size.0 * 2.0 - 1.0;
        let ndc_y = 1.0 - (y as f32 + 0.5) / self.size.1 * 2.0;
        let p = self.eye_from_clip * Vec4::new(ndc_x, ndc_y, 0.0, 1.0);
        // Any point of the ray, in front of the eye (the eye is the origin).
        let d = (p.truncate() / p.w).normalize_or_zero();
        if d.z > 0.0 {
            -d
        } else {
            d
        }
    }

    /// The radiance behind sample (`x`, `y`), clamped to [0, ceiling].
    pub(crate) fn radiance(&self, x: i32, y: i32) -> Vec3 {
        self.environment
            .background_radiance(self.direction(x, y))
            .clamp(Vec3::ZERO, Vec3::splat(self.ceiling))
    }
}

impl TileTarget {
    /// Fills the tile's sky planes from `sky` (every sample of the widened
    /// rows), or marks the tile as having a plain background colour.
    pub(crate) fn paint_sky(&mut self, sky: Option<&SkyView>) {
        let Some(sky) = sky else {
            self.sky_drawn = false;
            return;
        };
        let n = self.depth.len();
        for plane in &mut self.sky {
            plane.clear();
            plane.resize(n, f32x8::ZERO);
        }
        for row in 0..self.rect.height() {
            let y = self.rect.y0 + row;
            for block in 0..self.stride / LANES {
                let colors: [Vec3; LANES] =
                    std::array::from_fn(|k| sky.radiance(self.origin + (block * LANES + k) as i32, y));
                let lanes = [colors.map(|c| c.x), colors.map(|c| c.y), colors.map(|c| c.z)];
                let i = row as usize * self.stride / LANES + block;
                for (plane, l) in self.sky.iter_mut().zip(lanes) {
                    plane[i] = f32x8::from(l);
                }
            }
        }
        self.sky_drawn = true;
    }
}
