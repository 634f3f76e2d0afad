//! `zline._zline`: the native half of the `zline` Python package.
//!
//! One function, `render`, takes an input (a file by its name, or meshes
//! as raw little-endian arrays), the image's settings and a camera, and
//! returns the rendered layers as bytes; the Python half
//! (`python/zline/__init__.py`) turns them into numpy arrays and documents
//! the API. The scene is built and drawn by the same library calls as the
//! `zline render` command (`zline::load`, the framing, `zline::views`,
//! `zline::view::ViewChange`, the pipeline's depth, normal and object-ID
//! frames), so the arrays equal the command's PNGs byte for byte.

use std::path::PathBuf;
use std::sync::Arc;

use glam::{DMat3, DVec3, Vec3};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyDict};
use zline::io::LoadOptions;
use zline::pipeline::{DepthImage, Image, ObjectIds, RenderOptions, Renderer};
use zline::scene::{Camera, Mesh, Projection, Scene, ShadingMode};
use zline::shading::Material;
use zline::views::{NamedView, ProjectionKind};

create_exception!(
    _zline,
    ZlineError,
    PyException,
    "An input zline cannot read, or settings it cannot render: the message names the file and the problem."
);

/// One mesh given as arrays: positions (f32 x, y, z), triangles (u32
/// indices), optional unit normals (f32) and vertex colours (f32 r, g, b in
/// [0, 1]), all little-endian, and a name.
type MeshArrays = (Vec<u8>, Vec<u8>, Option<Vec<u8>>, Option<Vec<u8>>, String);

/// The camera the caller asked for (all `None`: zline's framing).
#[derive(Default)]
struct CameraArgs {
    eye: Option<[f32; 3]>,
    target: Option<[f32; 3]>,
    up: Option<[f32; 3]>,
    fov: Option<f32>,
    ortho_height: Option<f32>,
    intrinsics: Option<[f64; 4]>,
    pose: Option<[[f64; 4]; 4]>,
    near: Option<f32>,
    far: Option<f32>,
    view: Option<String>,
    projection: Option<String>,
    azimuth: Option<f32>,
    elevation: Option<f32>,
    zoom: Option<f32>,
}

fn error(message: impl std::fmt::Display) -> PyErr {
    ZlineError::new_err(message.to_string())
}

fn f32s(bytes: &[u8], what: &str) -> PyResult<Vec<f32>> {
    if !bytes.len().is_multiple_of(12) {
        return Err(error(format!("{what}: {} bytes is not a whole number of float32 triples", bytes.len())));
    }
    Ok(bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect())
}

fn vec3s(bytes: &[u8], what: &str) -> PyResult<Vec<Vec3>> {
    Ok(f32s(bytes, what)?.chunks_exact(3).map(Vec3::from_slice).collect())
}

/// The meshes as zline's, each with the default material (as STL and PLY
/// models get).
fn to_meshes(arrays: Vec<MeshArrays>) -> PyResult<Vec<Mesh>> {
    let mut out = Vec::with_capacity(arrays.len());
    for (i, (positions, triangles, normals, colors, name)) in arrays.into_iter().enumerate() {
        let label = if name.is_empty() { format!("mesh {i}") } else { name.clone() };
        let positions = vec3s(&positions, &format!("{label}: vertices"))?;
        if !triangles.len().is_multiple_of(12) {
            return Err(error(format!(
                "{label}: faces: {} bytes is not a whole number of uint32 triples",
                triangles.len()
            )));
        }
        let triangles: Vec<[u32; 3]> = triangles
            .chunks_exact(12)
            .map(|t| {
                std::array::from_fn(|k| {
                    u32::from_le_bytes([t[4 * k], t[4 * k + 1], t[4 * k + 2], t[4 * k + 3]])
                })
            })
            .collect();
        let normals = normals.map(|n| vec3s(&n, &format!("{label}: normals"))).transpose()?;
        let mesh = Mesh::new(name, positions, normals, triangles, Material::DEFAULT)
            .map_err(|e| error(format!("{label}: {e}")))?;
        let mesh = match colors {
            Some(c) => mesh
                .with_colors(vec3s(&c, &format!("{label}: colors"))?)
                .map_err(|e| error(format!("{label}: {e}")))?,
            None => mesh,
        };
        out.push(mesh);
    }
    Ok(out)
}

/// The camera of an intrinsic matrix and a camera-to-world pose in
/// OpenCV's axes (x right, y down, z forward): the frustum of SPEC §1 on
/// the image, near and far as given or fitted around the scene.
fn pinhole(
    scene: &Scene,
    k: [f64; 4],
    pose: [[f64; 4]; 4],
    near: Option<f32>,
    far: Option<f32>,
) -> PyResult<Camera> {
    let [fx, fy, cx, cy] = k;
    let (w, h) = (f64::from(scene.settings.width), f64::from(scene.settings.height));
    if !(fx.is_finite() && fy.is_finite() && fx > 0.0 && fy > 0.0 && cx.is_finite() && cy.is_finite()) {
        return Err(error(format!(
            "intrinsics: fx and fy must be finite and > 0, cx and cy finite; got {k:?}"
        )));
    }
    let r = DMat3::from_cols_array_2d(&[
        [pose[0][0], pose[1][0], pose[2][0]],
        [pose[0][1], pose[1][1], pose[2][1]],
        [pose[0][2], pose[1][2], pose[2][2]],
    ]);
    let eye = DVec3::new(pose[0][3], pose[1][3], pose[2][3]);
    let orthonormal = (r.transpose() * r).abs_diff_eq(DMat3::IDENTITY, 1e-4) && r.determinant() > 0.0;
    if !eye.is_finite() || !orthonormal {
        return Err(error(
            "pose: the upper 3×3 must be a rotation (orthonormal, determinant +1) and the translation finite",
        ));
    }
    let (forward, up) = (r.z_axis, -r.y_axis);
    let n = f64::from(near.unwrap_or(1.0));
    let frustum = Projection::Frustum {
        left: (-n * (cx + 0.5) / fx) as f32,
        right: (n * (w - cx - 0.5) / fx) as f32,
        bottom: (-n * (h - cy - 0.5) / fy) as f32,
        top: (n * (cy + 0.5) / fy) as f32,
        near: n as f32,
        far: far.unwrap_or((n * 1e4) as f32),
    };
    let mut camera = Camera {
        eye: eye.as_vec3(),
        target: (eye + forward).as_vec3(),
        up: up.as_vec3(),
        projection: frustum,
    };
    fit_planes(&mut camera, scene, near, far);
    Ok(camera)
}

/// Near and far fitted around the scene (the rule of `zline view`) where
/// the caller gave none.
fn fit_planes(camera: &mut Camera, scene: &Scene, near: Option<f32>, far: Option<f32>) {
    if near.is_some() && far.is_some() {
        return;
    }
    let given = camera.projection;
    zline::view::hug(camera, scene);
    let (fitted_near, fitted_far) = camera.projection.near_far();
    let (n, f) = (near.unwrap_or(fitted_near), far.unwrap_or(fitted_far));
    camera.projection = match given {
        Projection::Perspective { fovy_degrees, .. } => {
            Projection::Perspective { fovy_degrees, near: n, far: f }
        }
        Projection::Orthographic { height, .. } => Projection::Orthographic { height, near: n, far: f },
        Projection::Frustum { left, right, bottom, top, near: g, .. } => {
            let k = n / g;
            Projection::Frustum {
                left: left * k,
                right: right * k,
                bottom: bottom * k,
                top: top * k,
                near: n,
                far: f,
            }
        }
    };
}

/// Points the camera as the caller asked (see [`CameraArgs`]); the
/// framing path is `zline render`'s (`aim` in the CLI).
fn aim(scene: &mut Scene, c: &CameraArgs, framed: bool) -> PyResult<()> {
    if let Some(k) = c.intrinsics {
        let pose = c.pose.ok_or_else(|| error("intrinsics need a pose (camera-to-world, 4×4)"))?;
        scene.camera = pinhole(scene, k, pose, c.near, c.far)?;
        return Ok(());
    }
    if let (Some(eye), Some(target)) = (c.eye, c.target) {
        let near = c.near.unwrap_or(0.1);
        let far = c.far.unwrap_or(1000.0);
        let projection = match c.ortho_height {
            Some(height) => Projection::Orthographic { height, near, far },
            None => Projection::Perspective { fovy_degrees: c.fov.unwrap_or(45.0), near, far },
        };
        let up = Vec3::from(c.up.unwrap_or([0.0, 1.0, 0.0]));
        let mut camera = Camera { eye: eye.into(), target: target.into(), up, projection };
        fit_planes(&mut camera, scene, c.near, c.far);
        scene.camera = camera;
        return Ok(());
    }
    // `zline render`'s own path: the `Aim` its camera flags make.
    let view = c
        .view
        .as_deref()
        .map(|name| {
            NamedView::from_name(name).ok_or_else(|| {
                error(format!(
                    "view: unknown view {name:?}; expected front, back, left, right, top, bottom or iso"
                ))
            })
        })
        .transpose()?;
    let projection = c
        .projection
        .as_deref()
        .map(|kind| match kind {
            "perspective" => Ok(ProjectionKind::Perspective),
            "ortho" | "orthographic" => Ok(ProjectionKind::Orthographic),
            other => Err(error(format!("projection: expected perspective or ortho, got {other:?}"))),
        })
        .transpose()?;
    let change = zline::view::ViewChange {
        azimuth: c.azimuth,
        elevation: c.elevation,
        distance: None,
        zoom: c.zoom,
        fov: c.fov,
        up: c.up.map(Vec3::from),
    };
    zline::views::Aim { view, change, projection }.apply(scene, framed);
    Ok(())
}

fn shading(name: &str) -> PyResult<ShadingMode> {
    Ok(match name {
        "flat" => ShadingMode::Flat,
        "gouraud" => ShadingMode::Gouraud,
        "phong" => ShadingMode::Phong,
        other => return Err(error(format!("shading: expected flat, gouraud or phong, got {other:?}"))),
    })
}

/// What [`render`] draws and returns.
struct Frames {
    image: Image,
    depth: Option<DepthImage>,
    normals: Option<Image>,
    ids: Option<ObjectIds>,
}

fn draw(scene: &Scene, depth: bool, normals: bool, ids: bool) -> Result<Frames, String> {
    let options = RenderOptions::default();
    let mut renderer = Renderer::default();
    let mut image = Image::empty();
    let depth = if depth {
        let mut d = DepthImage::default();
        renderer.render_with_depth(scene, &options, &mut image, &mut d);
        Some(d)
    } else {
        renderer.render_into(scene, &options, &mut image);
        None
    };
    let normals = normals.then(|| {
        let mut n = Image::empty();
        renderer.render_normals_into(scene, &options, &mut n);
        n
    });
    let ids = if ids {
        let (mut frame, mut ids) = (Image::empty(), ObjectIds::default());
        renderer.render_object_ids_into(scene, &options, &mut frame, &mut ids).map_err(|e| e.to_string())?;
        Some(ids)
    } else {
        None
    };
    Ok(Frames { image, depth, normals, ids })
}

/// Renders a file (`path`: a model or a scene file, as `zline render`
/// reads it) or meshes (`meshes`), and returns a dict of bytes: `color`
/// (RGB, or RGBA with `transparent`), and when asked `depth` (float32 eye
/// depth, NaN where nothing), `normals` (RGB bytes, (n + 1)/2) and `ids`
/// (int32 object index, −1 where nothing); with `width`, `height`,
/// `channels` and the objects' `names`.
#[pyfunction]
#[pyo3(signature = (
    path=None, meshes=None, *, width=640, height=480, ssaa=1, shading_mode=None, background=None,
    transparent=false, depth=false, normals=false, ids=false, threads=None, allow_paths_outside=false, eye=None, target=None,
    up=None, fov=None, ortho_height=None, intrinsics=None, pose=None, near=None, far=None, view=None,
    projection=None, azimuth=None, elevation=None, zoom=None
))]
#[expect(clippy::too_many_arguments, reason = "Python keyword arguments, documented on the Python side")]
fn render<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    meshes: Option<Vec<MeshArrays>>,
    width: u32,
    height: u32,
    ssaa: u32,
    shading_mode: Option<String>,
    background: Option<[f32; 3]>,
    transparent: bool,
    depth: bool,
    normals: bool,
    ids: bool,
    threads: Option<usize>,
    allow_paths_outside: bool,
    eye: Option<[f32; 3]>,
    target: Option<[f32; 3]>,
    up: Option<[f32; 3]>,
    fov: Option<f32>,
    ortho_height: Option<f32>,
    intrinsics: Option<[f64; 4]>,
    pose: Option<[[f64; 4]; 4]>,
    near: Option<f32>,
    far: Option<f32>,
    view: Option<String>,
    projection: Option<String>,
    azimuth: Option<f32>,
    elevation: Option<f32>,
    zoom: Option<f32>,
) -> PyResult<Bound<'py, PyDict>> {
    let camera = CameraArgs {
        eye,
        target,
        up,
        fov,
        ortho_height,
        intrinsics,
        pose,
        near,
        far,
        view,
        projection,
        azimuth,
        elevation,
        zoom,
    };
    let mut warnings = Vec::new();
    let mut scene = match (path, meshes) {
        (Some(path), None) => {
            let loaded = zline::load::load(&path, LoadOptions { allow_outside: allow_paths_outside })
                .map_err(|e| error(zline::error_line(&e)))?;
            warnings = loaded.warnings;
            if loaded.scene.settings.renderer != zline::scene::trace_options::Renderer::Raster {
                warnings.push(format!(
                    "{}: the scene asks for the {} renderer; zline.render draws it with the rasterizer",
                    path.display(),
                    loaded.scene.settings.renderer.name()
                ));
            }
            loaded.scene
        }
        (None, Some(arrays)) => {
            let meshes = to_meshes(arrays)?;
            if meshes.is_empty() {
                return Err(error("meshes: no mesh given"));
            }
            zline::io::scene_for_model(meshes, Default::default())
        }
        _ => return Err(error("give either a path or meshes")),
    };
    if width == 0
        || height == 0
        || width > zline::scene::MAX_IMAGE_SIDE
        || height > zline::scene::MAX_IMAGE_SIDE
    {
        return Err(error(format!(
            "size: {width}x{height}; each side must be 1 to {} pixels",
            zline::scene::MAX_IMAGE_SIDE
        )));
    }
    if ssaa == 0 || ssaa > zline::scene::MAX_SSAA {
        return Err(error(format!("ssaa: {ssaa}; expected 1 to {}", zline::scene::MAX_SSAA)));
    }
    // Judged before the size changes, as `zline render` does.
    let framed = zline::view::is_framed(&scene);
    let s = &mut scene.settings;
    (s.width, s.height, s.ssaa) = (width, height, ssaa);
    if let Some(name) = &shading_mode {
        s.shading = shading(name)?;
    }
    if transparent {
        s.transparent_background = true;
    }
    aim(&mut scene, &camera, framed)?;
    if let Some(c) = background {
        scene.background = Vec3::from(c);
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0).min(zline::scene::MAX_THREADS))
        .build()
        .map_err(|e| error(format!("cannot start the worker threads: {e}")))?;
    let scene = Arc::new(scene);
    let shared = Arc::clone(&scene);
    let frames = py.detach(move || pool.install(|| draw(&shared, depth, normals, ids))).map_err(error)?;
    let out = PyDict::new(py);
    let Frames { image, depth, normals, ids } = frames;
    let channels = if image.transparent { 4 } else { 3 };
    let color = if image.transparent { image.to_rgba() } else { image.to_rgb() };
    out.set_item("width", image.width)?;
    out.set_item("height", image.height)?;
    out.set_item("channels", channels)?;
    out.set_item("color", PyByteArray::new(py, &color))?;
    if let Some(d) = depth {
        let bytes: Vec<u8> = d.depth.iter().flat_map(|v| v.to_le_bytes()).collect();
        out.set_item("depth", PyByteArray::new(py, &bytes))?;
    }
    if let Some(n) = normals {
        out.set_item("normals", PyByteArray::new(py, &n.to_rgb()))?;
    }
    if let Some(ids) = ids {
        let bytes: Vec<u8> = ids.ids.iter().flat_map(|v| v.to_le_bytes()).collect();
        out.set_item("ids", PyByteArray::new(py, &bytes))?;
    }
    let names: Vec<String> = scene.objects.iter().map(|o| o.mesh.name.clone()).collect();
    out.set_item("names", names)?;
    out.set_item("warnings", warnings)?;
    Ok(out)
}

/// The module `zline._zline`.
#[pymodule]
fn _zline(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add("ZlineError", m.py().get_type::<ZlineError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
