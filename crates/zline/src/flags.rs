//! The rendering flags applied to a loaded scene: camera, fog, shadows,
//! the lighting model and the render settings (the flags override what the
//! scene file says).

use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec3;
use zline::scene::{
    DepthMode, Fog, FogCoordinate, GouraudClamp, Interpolation, LightingSides, Mesh, RenderSettings, Scene,
    ShadingMode, ShadowMode,
};
use zline::shading::{Filter, ModelChoice};

use zline::views::{NamedView, ProjectionKind};

use crate::cli::choices::{
    Clamp, Depth, FogCoord, Interp, ProjectionName as Projection, Shading, ShadowFilter, Sides, TexFilter,
};
use crate::cli::common::Common;

/// The camera flags and `--background`; a framed model is framed again
/// for the final aspect ratio first. `turn` adds degrees to `--azimuth`
/// (a turntable's frames). The named view (`view`, else `--view`) comes
/// first, the orbit and zoom flags after it, the projection last.
pub(crate) fn apply_camera(scene: &mut Scene, common: &Common, framed: bool, turn: f32) {
    aim(scene, common, common.view, framed, turn);
}

/// [`apply_camera`] from the named view `view`.
pub(crate) fn aim(scene: &mut Scene, common: &Common, view: Option<NamedView>, framed: bool, turn: f32) {
    let change = zline::view::ViewChange {
        azimuth: if turn == 0.0 { common.azimuth } else { Some(common.azimuth.unwrap_or(0.0) + turn) },
        elevation: common.elevation,
        distance: common.distance,
        zoom: common.zoom,
        fov: common.fov,
        up: common.up,
    };
    let projection = common.projection.map(|kind| match kind {
        Projection::Perspective => ProjectionKind::Perspective,
        Projection::Ortho => ProjectionKind::Orthographic,
    });
    zline::views::Aim { view, change, projection }.apply(scene, framed);
    if let Some(c) = common.background {
        scene.background = c;
    }
}

/// The CLI's fog flags over the scene's fog: `--fog` sets the mode (keeping
/// the scene's colour and coordinate if it had fog), the others adjust an
/// existing fog.
pub(crate) fn apply_fog(scene: &mut Scene, common: &Common) {
    if let Some(mode) = common.fog {
        let base =
            scene.fog.unwrap_or(Fog { mode, color: Vec3::splat(0.5), coordinate: FogCoordinate::EyePlane });
        scene.fog = Some(Fog { mode, ..base });
    }
    if let Some(fog) = &mut scene.fog {
        if let Some(c) = common.fog_color {
            fog.color = c;
        }
        if let Some(c) = common.fog_coordinate {
            fog.coordinate = match c {
                FogCoord::EyePlane => FogCoordinate::EyePlane,
                FogCoord::Radial => FogCoordinate::Radial,
            };
        }
    }
}

/// `--shadows`, `--shadow-map-size` and `--shadow-filter` over the
/// scene's; planar shadows with no receiving plane draw none, which is
/// worth a warning.
pub(crate) fn apply_shadows(scene: &mut Scene, common: &Common) {
    if let Some(size) = common.shadow_map_size {
        scene.shadows.map_size = size;
    }
    if let Some(filter) = common.shadow_filter {
        scene.shadows.pcf = matches!(filter, ShadowFilter::Pcf);
    }
    let Some(mode) = common.shadows else { return };
    scene.shadows.mode = mode.into();
    if scene.shadows.mode == ShadowMode::Planar && scene.shadows.planes.is_empty() {
        eprintln!("warning: --shadows planar: the scene has no shadow_plane objects");
    }
}

/// `--model`: every object's material and every mesh's lit by the chosen
/// model ([`Material::with_model`](zline::shading::Material::with_model)).
/// A mesh shared by several objects is changed once and stays shared.
pub(crate) fn apply_model(scene: &mut Scene, common: &Common) {
    let Some(choice) = common.model else { return };
    let choice = ModelChoice::from(choice);
    let mut changed: HashMap<*const Mesh, Arc<Mesh>> = HashMap::new();
    for object in &mut scene.objects {
        object.material = object.material.map(|m| m.with_model(choice));
        let material = object.mesh.material.with_model(choice);
        if material != object.mesh.material {
            let mesh = changed
                .entry(Arc::as_ptr(&object.mesh))
                .or_insert_with(|| Arc::new(Mesh { material, ..(*object.mesh).clone() }));
            object.mesh = Arc::clone(mesh);
        }
    }
}

/// `--environment` (loaded and prepared, replacing the scene's),
/// `--environment-intensity`, `--environment-rotation` and
/// `--environment-background` over the scene's environment; the last three
/// without an environment are worth a warning.
pub(crate) fn apply_environment(scene: &mut Scene, common: &Common) -> anyhow::Result<()> {
    if let Some(spec) = &common.environment {
        let (light, warnings) = zline::io::load_environment(spec)?;
        for w in warnings {
            eprintln!("warning: {w}");
        }
        let keep = scene.environment.take();
        let mut environment = zline::shading::Environment::new(light);
        if let Some(old) = keep {
            (environment.intensity, environment.rotation_degrees) = (old.intensity, old.rotation_degrees);
            environment.background = old.background;
        }
        scene.environment = Some(environment);
    }
    let adjusting = common.environment_intensity.is_some()
        || common.environment_rotation.is_some()
        || common.environment_background;
    let Some(environment) = &mut scene.environment else {
        if adjusting {
            eprintln!("warning: --environment-*: the scene has no environment map (give --environment)");
        }
        return Ok(());
    };
    if let Some(x) = common.environment_intensity {
        environment.intensity = x;
    }
    if let Some(deg) = common.environment_rotation {
        environment.rotation_degrees = deg;
    }
    environment.background |= common.environment_background;
    Ok(())
}

/// The render-setting flags (size, shading, filter, adaptive, ssaa, depth,
/// clamp, lighting sides, interpolation, visibility, layers) over the
/// scene's settings.
pub(crate) fn apply_overrides(settings: &mut RenderSettings, common: &Common) {
    if let Some((w, h)) = common.size {
        settings.width = w;
        settings.height = h;
    }
    if let Some(s) = common.shading {
        settings.shading = match s {
            Shading::Flat => ShadingMode::Flat,
            Shading::Gouraud => ShadingMode::Gouraud,
            Shading::Phong => ShadingMode::Phong,
        };
    }
    if let Some(f) = common.filter {
        settings.texture_filter = Some(match f {
            TexFilter::Nearest => Filter::Nearest,
            TexFilter::Bilinear => Filter::Bilinear,
            TexFilter::Trilinear => Filter::Trilinear,
        });
    }
    if let Some(t) = common.adaptive {
        settings.adaptive_tolerance = Some(t);
    }
    if let Some(t) = common.tonemap {
        settings.tone_mapping.operator = t.into();
    }
    if let Some(x) = common.exposure {
        settings.tone_mapping.exposure = x;
    }
    if let Some(n) = common.ssaa {
        settings.ssaa = n;
    }
    if let Some(d) = common.depth {
        settings.depth = match d {
            Depth::Normalized => DepthMode::Normalized,
            Depth::Reversed => DepthMode::ReversedFloat,
        };
    }
    if let Some(c) = common.gouraud_clamp {
        settings.gouraud_clamp = match c {
            Clamp::Vertex => GouraudClamp::PerVertex,
            Clamp::Sample => GouraudClamp::PerSample,
        };
    }
    if let Some(l) = common.lighting {
        settings.lighting_sides = match l {
            Sides::TwoSided => LightingSides::TwoSided,
            Sides::OneSided => LightingSides::OneSided,
        };
    }
    if let Some(i) = common.interpolation {
        settings.interpolation = match i {
            Interp::Perspective => Interpolation::PerspectiveCorrect,
            Interp::Linear => Interpolation::ScreenLinear,
        };
    }
    common.visibility.apply(settings);
    common.layers.apply(settings);
}
