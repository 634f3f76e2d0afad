//! The view of a scene file: its `[camera]`, `[fog]` and `[environment]`
//! tables, checked into a [`Camera`], a [`Fog`] and an [`Environment`].

use std::path::Path;

use glam::Vec3;
use serde::Deserialize;
use zline_scene::{Camera, Projection};
use zline_shading::{Environment, Fog, FogCoordinate, FogMode};

use super::checks::{Checker, Result, S};
use crate::environment_file::{load_environment, SKY_NAME};
use crate::files::{resolve, LoadOptions};
use crate::framing::camera_is_finite;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FogDef {
    pub(super) mode: FogKind,
    pub(super) start: Option<S<f32>>,
    pub(super) end: Option<S<f32>>,
    pub(super) density: Option<S<f32>>,
    pub(super) color: Option<S<[f32; 3]>>,
    pub(super) coordinate: Option<FogCoordinateDef>,
}

#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum FogKind {
    Linear,
    Exp,
    Exp2,
}

#[derive(Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub(super) enum FogCoordinateDef {
    EyePlane,
    Radial,
}

#[derive(Clone, Copy, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum ProjectionDef {
    #[default]
    Perspective,
    Orthographic,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraDef {
    pub(super) eye: S<[f32; 3]>,
    pub(super) target: Option<S<[f32; 3]>>,
    pub(super) up: Option<S<[f32; 3]>>,
    #[serde(default)]
    pub(super) projection: ProjectionDef,
    pub(super) fovy: Option<S<f32>>,
    pub(super) height: Option<S<f32>>,
    pub(super) near: Option<S<f32>>,
    pub(super) far: Option<S<f32>>,
}

/// The camera a `[camera]` table describes; near and far default to planes
/// hugging `bounds` (the scene's world box), and `aspect` is the image's.
pub(super) fn camera(
    check: &Checker<'_>,
    def: &S<CameraDef>,
    bounds: (Vec3, Vec3),
    aspect: f32,
) -> Result<Camera> {
    let c = def.get_ref();
    let eye = check.vec3(&c.eye, "camera.eye")?;
    let target = c.target.as_ref().map_or(Ok(Vec3::ZERO), |t| check.vec3(t, "camera.target"))?;
    let up = c.up.as_ref().map_or(Ok(Vec3::Y), |u| check.vec3(u, "camera.up"))?;
    if eye == target {
        return Err(check.error(c.eye.span(), "camera.eye", "must differ from camera.target"));
    }
    let direction = target - eye;
    if (direction / direction.abs().max_element()).cross(up).length() < 1e-6 {
        let span = c.up.as_ref().map_or(def.span(), |u| u.span());
        return Err(check.error(span, "camera.up", "must not be parallel to the view direction"));
    }
    let fitted = fitted_depth_range(eye, target, bounds);
    let near = check.optional(&c.near, "camera.near", fitted.0, f32::MIN, f32::MAX)?;
    let far = check.optional(&c.far, "camera.far", fitted.1, f32::MIN, f32::MAX)?;
    let projection = match c.projection {
        ProjectionDef::Perspective => {
            let fovy = check.optional(&c.fovy, "camera.fovy", 45.0, 0.0, 180.0)?;
            if fovy <= 0.0 || fovy >= 180.0 {
                return Err(check.value_error(
                    c.fovy.as_ref(),
                    def,
                    "camera.fovy",
                    "must be in (0, 180) degrees",
                ));
            }
            if near <= 0.0 {
                return Err(check.value_error(
                    c.near.as_ref(),
                    def,
                    "camera.near",
                    "must be > 0 for perspective",
                ));
            }
            Projection::Perspective { fovy_degrees: fovy, near, far }
        }
        ProjectionDef::Orthographic => {
            let fitted_height = 2.2 * (bounds.1 - bounds.0).length().max(1e-6) / 2.0;
            let height = check.optional(&c.height, "camera.height", fitted_height, 0.0, f32::MAX)?;
            if height <= 0.0 {
                return Err(check.value_error(c.height.as_ref(), def, "camera.height", "must be > 0"));
            }
            Projection::Orthographic { height, near, far }
        }
    };
    if far <= near {
        let message = format!("must be greater than camera.near ({near}), got {far}");
        return Err(check.value_error(c.far.as_ref(), def, "camera.far", message));
    }
    let camera = Camera { eye, target, up, projection };
    if !camera_is_finite(&camera, aspect) {
        return Err(check.error(def.span(), "camera", "its values give a non-finite projection"));
    }
    Ok(camera)
}

/// The fog a `[fog]` table describes.
pub(super) fn fog(check: &Checker<'_>, def: &S<FogDef>) -> Result<Fog> {
    let f = def.get_ref();
    let color = match &f.color {
        Some(c) => check.vec3_in(c, "fog.color", 0.0, 1.0)?,
        None => Vec3::splat(0.5),
    };
    let mode = match f.mode {
        FogKind::Linear => {
            check.not_allowed(&f.density, "fog", "density", "linear fog")?;
            let start = check.optional(&f.start, "fog.start", 0.0, 0.0, f32::MAX)?;
            let end = check.optional(&f.end, "fog.end", 1.0, 0.0, f32::MAX)?;
            if end < start {
                let span = f.end.as_ref().map_or(def.span(), |e| e.span());
                return Err(check.error(span, "fog.end", format!("must be ≥ start ({start}), got {end}")));
            }
            FogMode::Linear { start, end }
        }
        FogKind::Exp | FogKind::Exp2 => {
            check.not_allowed(&f.start, "fog", "start", "exponential fog")?;
            check.not_allowed(&f.end, "fog", "end", "exponential fog")?;
            let density = check.optional(&f.density, "fog.density", 1.0, 0.0, f32::MAX)?;
            match f.mode {
                FogKind::Exp => FogMode::Exponential { density },
                _ => FogMode::SquaredExponential { density },
            }
        }
    };
    let coordinate = match f.coordinate {
        Some(FogCoordinateDef::Radial) => FogCoordinate::Radial,
        _ => FogCoordinate::EyePlane,
    };
    Ok(Fog { mode, color, coordinate })
}

/// Near and far planes hugging the scene's bounding sphere seen from `eye`
/// along the view direction.
fn fitted_depth_range(eye: Vec3, target: Vec3, (min, max): (Vec3, Vec3)) -> (f32, f32) {
    let (eye, target) = (eye.as_dvec3(), target.as_dvec3());
    let center = (min.as_dvec3() + max.as_dvec3()) / 2.0;
    let radius = ((max.as_dvec3() - min.as_dvec3()).length() / 2.0).max(1e-6);
    let forward = (target - eye).normalize();
    let d = (center - eye).dot(forward);
    let far = (d + 1.1 * radius).max(radius);
    let near = (d - 1.1 * radius).max(far * 1e-4);
    (near as f32, far as f32)
}

/// The `[environment]` table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct EnvironmentDef {
    pub(super) file: S<String>,
    pub(super) intensity: Option<S<f32>>,
    pub(super) rotation: Option<S<f32>>,
    pub(super) background: Option<bool>,
}

/// The `[environment]` table: the panorama loaded and prepared (see
/// `load_environment`), its intensity ≥ 0, rotation in degrees, and
/// whether it is drawn as the background.
pub(super) fn environment(
    check: &Checker<'_>,
    def: &S<EnvironmentDef>,
    options: LoadOptions,
) -> Result<Environment> {
    let e = def.get_ref();
    let intensity = check.optional(&e.intensity, "environment.intensity", 1.0, 0.0, f32::MAX)?;
    let rotation = check.optional(&e.rotation, "environment.rotation", 0.0, -1e6, 1e6)?;
    let name = Path::new(e.file.get_ref());
    let light = if name == Path::new(SKY_NAME) {
        load_environment(name)
    } else {
        let path = resolve(check.path, name, options)
            .map_err(|why| check.error(e.file.span(), "environment.file", why))?;
        load_environment(&path)
    };
    let (light, warnings) = light.map_err(|err| check.error(e.file.span(), "environment.file", err))?;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    let mut environment = Environment::new(light);
    environment.intensity = intensity;
    environment.rotation_degrees = rotation;
    environment.background = e.background.unwrap_or(false);
    Ok(environment)
}
