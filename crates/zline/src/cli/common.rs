//! The rendering flags every command shares (output, size, shading, fog,
//! shadows, camera, …): parsed by clap, applied by `crate::flags`.

use std::path::PathBuf;

use clap::Args;
use glam::Vec3;
use zline::pipeline::RenderOptions;
use zline::scene::{FogMode, MAX_SHADOW_MAP_SIZE, MAX_TILE_SIZE, MIN_TILE_SIZE};

use super::choices::{
    Clamp, Depth, FogCoord, Interp, LightModel, Shading, ShadowFilter, Shadows, Sides, TexFilter, Tonemap,
};
use super::parse::{
    parse_angle, parse_color, parse_direction, parse_fog, parse_fov, parse_non_negative, parse_positive,
    parse_size, parse_tolerance, parse_view, parse_views,
};

/// The smallest `--shadow-map-size`, as the scene file's.
const MIN_SHADOW_MAP_SIZE: u32 = 16;

#[derive(Args)]
pub(crate) struct Common {
    /// Output image: .png, or .jpg/.jpeg for JPEG at quality 90; `-`: a
    /// PNG on standard output. Written to a temporary file in the same
    /// folder, then renamed over OUT: a failed write leaves an existing
    /// file as it was.
    #[arg(short, long, value_name = "OUT.png")]
    pub(crate) output: PathBuf,
    /// Also print the time of each step: load, render, PNG encode and write.
    #[arg(long)]
    pub(crate) timings: bool,
    /// Print no `wrote …` lines on success, and with `batch` and
    /// `turntable` no progress bar and no per-file lines: only warnings,
    /// errors (and, when some failed, a batch's summary).
    #[arg(short, long)]
    pub(crate) quiet: bool,
    /// Image size, e.g. 1280x720 (default: the scene's, or 800x600).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// Shading mode for objects that do not set their own.
    #[arg(long, value_enum)]
    pub(crate) shading: Option<Shading>,
    /// Light every material with this model (replaces the files' own):
    /// `cook-torrance` is Cook–Torrance with GGX, `beckmann` with the
    /// Beckmann distribution (docs/SPEC.md §5.2).
    #[arg(long, value_enum)]
    pub(crate) model: Option<LightModel>,
    /// Light from an environment map (docs/SPEC.md §5.3): a Radiance HDR
    /// equirectangular panorama, or `sky` for the built-in procedural sky.
    /// Replaces the scene's; adds to its ambient light.
    #[arg(long, value_name = "FILE.hdr|sky")]
    pub(crate) environment: Option<PathBuf>,
    /// Multiplies the environment's radiance (default: the scene's, or 1).
    #[arg(long, value_name = "X", value_parser = parse_non_negative)]
    pub(crate) environment_intensity: Option<f32>,
    /// Turns the environment about +y, in degrees counter-clockwise seen
    /// from above (default: the scene's, or 0).
    #[arg(long, value_name = "DEG", value_parser = parse_angle)]
    pub(crate) environment_rotation: Option<f32>,
    /// Draw the environment where no surface is, instead of the background
    /// colour.
    #[arg(long)]
    pub(crate) environment_background: bool,
    /// Tone mapping before the 8-bit output (docs/SPEC.md §10; replaces
    /// `[render] tonemap`): `none` clamps; the operators end in sRGB.
    #[arg(long, value_enum)]
    pub(crate) tonemap: Option<Tonemap>,
    /// Multiplies the linear colour before the tone mapping (replaces
    /// `[render] exposure`; default 1).
    #[arg(long, value_name = "X", value_parser = parse_non_negative)]
    pub(crate) exposure: Option<f32>,
    /// Attribute interpolation.
    #[arg(long, value_enum)]
    pub(crate) interpolation: Option<Interp>,
    /// Worker threads (default: one per core; more than 256 are taken as
    /// 256, with a warning).
    #[arg(long, value_name = "N")]
    pub(crate) threads: Option<usize>,
    /// Texture filtering for every texture (default: each texture's own).
    #[arg(long, value_enum)]
    pub(crate) filter: Option<TexFilter>,
    /// Fog (replaces the scene's): linear:START:END, exp:DENSITY or
    /// exp2:DENSITY, distances in world units.
    #[arg(long, value_name = "MODE", value_parser = parse_fog)]
    pub(crate) fog: Option<FogMode>,
    /// Fog colour as R,G,B in [0, 1] (default: the scene's, or 0.5 grey).
    #[arg(long, value_name = "R,G,B", value_parser = parse_color)]
    pub(crate) fog_color: Option<Vec3>,
    /// Fog coordinate: distance to the eye plane or to the eye.
    #[arg(long, value_enum)]
    pub(crate) fog_coordinate: Option<FogCoord>,
    /// Supersampling: N×N samples per pixel, box-filtered (1 = off). A
    /// frame has at most 2^28 samples (width × height × N²).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=zline::scene::MAX_SSAA as i64))]
    pub(crate) ssaa: Option<u32>,
    /// Adaptive mode: per triangle, the cheapest evaluation whose colour
    /// provably stays within TOL 8-bit steps of the full one.
    #[arg(long, value_name = "TOL", value_parser = parse_tolerance)]
    pub(crate) adaptive: Option<f32>,
    /// What the depth buffer stores.
    #[arg(long, value_enum)]
    pub(crate) depth: Option<Depth>,
    /// Where untextured Gouraud shading clamps the lit colour (docs/SPEC.md §11).
    #[arg(long, value_enum)]
    pub(crate) gouraud_clamp: Option<Clamp>,
    /// How back faces drawn without culling are lit (docs/SPEC.md §11).
    #[arg(long, value_enum)]
    pub(crate) lighting: Option<Sides>,
    /// Shadows (replaces the scene file's `[render] shadows`): planar ones
    /// fall on the scene file's `shadow_plane` objects; shadow maps fall on
    /// every object, from every object.
    #[arg(long, value_enum)]
    pub(crate) shadows: Option<Shadows>,
    /// Shadow map side in texels, 16..=8192 (a point light renders six such
    /// faces); replaces `[render] shadow_map_size`, default 1024.
    #[arg(
        long,
        value_name = "N",
        value_parser = clap::value_parser!(u32).range(MIN_SHADOW_MAP_SIZE as i64..=MAX_SHADOW_MAP_SIZE as i64)
    )]
    pub(crate) shadow_map_size: Option<u32>,
    /// How shadow maps are sampled (replaces `[render] shadow_filter`).
    #[arg(long, value_enum)]
    pub(crate) shadow_filter: Option<ShadowFilter>,
    /// Turn the camera about its target by this many degrees about the up
    /// vector (positive: the camera moves to its right).
    #[arg(long, value_name = "DEG", value_parser = parse_angle, allow_hyphen_values = true, help_heading = "Camera")]
    pub(crate) azimuth: Option<f32>,
    /// Raise the camera by this many degrees towards up (stops 1° short
    /// of straight above or below).
    #[arg(long, value_name = "DEG", value_parser = parse_angle, allow_hyphen_values = true, help_heading = "Camera")]
    pub(crate) elevation: Option<f32>,
    /// The camera's distance from its target, in world units.
    #[arg(long, value_name = "D", value_parser = parse_positive, help_heading = "Camera")]
    pub(crate) distance: Option<f32>,
    /// Magnify by this factor (2: twice as close, or half the view height
    /// of an orthographic camera).
    #[arg(long, value_name = "F", value_parser = parse_positive, help_heading = "Camera")]
    pub(crate) zoom: Option<f32>,
    /// Vertical field of view in degrees (1..=179), perspective cameras.
    #[arg(long, value_name = "DEG", value_parser = parse_fov, help_heading = "Camera")]
    pub(crate) fov: Option<f32>,
    /// The world's up direction (default: the scene's, +y for models).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_direction, allow_hyphen_values = true, help_heading = "Camera")]
    pub(crate) up: Option<Vec3>,
    /// Look from a named side: front (from +z), back, left, right (from
    /// +x), top (from +y), bottom or iso (from (1, 1, 1)); a model is framed
    /// again along it.
    #[arg(long, value_name = "front|back|left|right|top|bottom|iso", value_parser = parse_view, help_heading = "Camera")]
    pub(crate) view: Option<zline::views::NamedView>,
    /// The camera's projection; ortho frames a model's tight box.
    #[arg(long, value_enum, help_heading = "Camera")]
    pub(crate) projection: Option<super::choices::ProjectionName>,
    /// `render` and `demo`: write one contact sheet of these views
    /// (comma-separated names as for --view, or `all`), each cell the
    /// image size, named under it.
    #[arg(long, value_name = "LIST", value_parser = parse_views, conflicts_with = "view", help_heading = "Camera")]
    pub(crate) views: Option<super::parse::ViewList>,
    /// Background colour, each channel in [0, 1].
    #[arg(long, value_name = "R,G,B", value_parser = parse_color)]
    pub(crate) background: Option<Vec3>,
    /// A height map (PNG or JPEG, red channel) on every mesh with texture
    /// coordinates: bump mapping in Phong shading (flat and Gouraud ignore
    /// it), with MikkTSpace tangents.
    #[arg(long, value_name = "FILE")]
    pub(crate) bump: Option<PathBuf>,
    /// The bump map's scale k: a white texel's height in texture
    /// coordinate units (the normal tilts by atan(k·∂h/∂s) along s).
    #[arg(long, value_name = "K", default_value_t = 1.0, requires = "bump")]
    pub(crate) bump_scale: f32,
    /// Draw without bump and normal maps (the files' and --bump's): the
    /// interpolated normal alone, as before they existed.
    #[arg(long, conflicts_with = "bump")]
    pub(crate) no_normal_maps: bool,
    /// Tile edge in pixels, 8..=1024; the image does not depend on it.
    #[arg(
        long,
        value_name = "PIXELS",
        default_value_t = RenderOptions::default().tile_size,
        value_parser = clap::value_parser!(u32).range(MIN_TILE_SIZE as i64..=MAX_TILE_SIZE as i64)
    )]
    pub(crate) tile_size: u32,
    #[command(flatten)]
    pub(crate) visibility: super::visibility::VisibilityArgs,
    #[command(flatten)]
    pub(crate) layers: super::layers::LayerArgs,
    #[command(flatten)]
    pub(crate) trace: super::trace::TraceArgs,
    #[command(flatten)]
    pub(crate) radiosity: super::radiosity::RadiosityArgs,
}
