//! Named views, the projection switch and contact sheets: what a
//! thumbnail or a render check asks of the camera without knowing the
//! model (`--view`, `--projection`, `--views`).
//!
//! - A **named view** looks at the scene from a world axis (+y up, the
//!   models' convention): `front` from +z, `back` from −z, `right` from +x,
//!   `left` from −x, `top` from +y (image up −z, so the front is at the
//!   bottom), `bottom` from −y (image up +z), `iso` from (1, 1, 1). A
//!   framed scene (a bare model, a scene file without `[camera]`) is framed
//!   again along it; a file's own camera keeps its target and distance.
//!   zline's default key and fill lights (a bare model's) turn with the
//!   camera, from the framing's direction to the view's, so that every
//!   side is lit as the framing lights the front; a scene's own lights
//!   stay.
//! - **Orthographic**: a framed scene gets the tight box of its vertices
//!   seen along the view (the target moved to its centre, 5 % margin); a
//!   file's camera keeps what its perspective showed at the target's
//!   distance, height 2·d·tan(fovy/2). **Perspective** from an orthographic
//!   camera: 45°, the distance that shows the same height at the target.
//! - A **contact sheet** lays cells out in rows under their names (the
//!   8 × 8 bitmap font of `font8x8`, twice its size).

use font8x8::legacy::BASIC_LEGACY;
use glam::{Mat3, Vec3};
use zline_pipeline::Image;
use zline_scene::{Camera, Projection, Scene};
use zline_shading::Light;

/// A view along a world axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NamedView {
    /// From +z.
    Front,
    /// From −z.
    Back,
    /// From −x.
    Left,
    /// From +x.
    Right,
    /// From +y, image up −z.
    Top,
    /// From −y, image up +z.
    Bottom,
    /// From (1, 1, 1).
    Iso,
}

impl NamedView {
    /// Every view, in the order a sheet of all of them shows.
    pub const ALL: [NamedView; 7] = [
        NamedView::Front,
        NamedView::Back,
        NamedView::Left,
        NamedView::Right,
        NamedView::Top,
        NamedView::Bottom,
        NamedView::Iso,
    ];

    /// The name the command line uses.
    pub fn name(self) -> &'static str {
        match self {
            NamedView::Front => "front",
            NamedView::Back => "back",
            NamedView::Left => "left",
            NamedView::Right => "right",
            NamedView::Top => "top",
            NamedView::Bottom => "bottom",
            NamedView::Iso => "iso",
        }
    }

    /// The view named `name`, if any.
    pub fn from_name(name: &str) -> Option<NamedView> {
        NamedView::ALL.into_iter().find(|v| v.name() == name)
    }

    /// The unit direction from the target to the eye, and the camera's up.
    pub fn direction(self) -> (Vec3, Vec3) {
        match self {
            NamedView::Front => (Vec3::Z, Vec3::Y),
            NamedView::Back => (Vec3::NEG_Z, Vec3::Y),
            NamedView::Left => (Vec3::NEG_X, Vec3::Y),
            NamedView::Right => (Vec3::X, Vec3::Y),
            NamedView::Top => (Vec3::Y, Vec3::NEG_Z),
            NamedView::Bottom => (Vec3::NEG_Y, Vec3::Z),
            NamedView::Iso => (Vec3::ONE.normalize(), Vec3::Y),
        }
    }

    /// Points `scene`'s camera along the view (module doc); `framed` says
    /// the camera is zline's framing.
    pub fn apply(self, scene: &mut Scene, aspect: f32, framed: bool) {
        let (back, up) = self.direction();
        let camera = scene.camera;
        let fitted = match (framed, camera.projection) {
            (true, Projection::Perspective { fovy_degrees, .. }) => {
                zline_io::fit_camera(&scene.objects, back, up, fovy_degrees, aspect)
            }
            _ => None,
        };
        let mut camera = fitted.unwrap_or_else(|| {
            let distance = (camera.eye - camera.target).length();
            let distance = if distance.is_finite() && distance > 0.0 { distance } else { 1.0 };
            Camera { eye: camera.target + back * distance, up, ..camera }
        });
        crate::view::hug(&mut camera, scene);
        scene.camera = camera;
        if scene.lights == zline_io::default_lights() {
            let turn = basis(back, up) * basis(zline_io::VIEW_DIRECTION, Vec3::Y).transpose();
            for light in &mut scene.lights {
                if let Light::Directional { direction, .. } = light {
                    *direction = turn * *direction;
                }
            }
        }
    }
}

/// The camera frame (right, up, back) looking from `back` with `up`.
fn basis(back: Vec3, up: Vec3) -> Mat3 {
    let back = back.normalize_or(Vec3::Z);
    let right = up.cross(back).normalize_or(back.any_orthonormal_vector());
    Mat3::from_cols(right, back.cross(right), back)
}

/// The camera's projection asked for by `--projection`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProjectionKind {
    /// A perspective camera.
    Perspective,
    /// An orthographic camera.
    Orthographic,
}

/// What a command asks of a scene's camera: a named view, then orbit,
/// distance, zoom, field of view and up, then a projection. `render`'s
/// camera flags and the Python module's keyword arguments both come here,
/// so the two point the camera alike, to the bit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Aim {
    /// `--view`.
    pub view: Option<NamedView>,
    /// `--azimuth`, `--elevation`, `--distance`, `--zoom`, `--fov`, `--up`.
    pub change: crate::view::ViewChange,
    /// `--projection`.
    pub projection: Option<ProjectionKind>,
}

impl Aim {
    /// Points `scene`'s camera: zline's framing of the objects again for
    /// the image's aspect when `framed` (a bare model, or a scene file
    /// without a camera), the named view, the changes, the projection (a
    /// zoom also divides a framed orthographic view's height).
    pub fn apply(&self, scene: &mut Scene, framed: bool) {
        let aspect = crate::view::aspect_of(scene);
        if framed {
            scene.camera = zline_io::model_camera(&scene.objects, aspect);
        }
        if let Some(view) = self.view {
            view.apply(scene, aspect, framed);
        }
        self.change.apply(scene, aspect, framed);
        if let Some(kind) = self.projection {
            set_projection(scene, kind, aspect, framed);
            let zoom = self.change.zoom.filter(|z| z.is_finite() && *z > 0.0);
            if let (Some(z), Projection::Orthographic { height, .. }) = (zoom, &mut scene.camera.projection) {
                if kind == ProjectionKind::Orthographic && framed {
                    *height /= z;
                }
            }
        }
    }
}

/// The vertical field of view a perspective camera made from an
/// orthographic one gets.
pub const ORTHO_TO_PERSPECTIVE_FOVY: f32 = 45.0;
/// The margin around a framed orthographic view, a share of its height.
const ORTHO_MARGIN: f32 = 0.05;

/// Switches `scene`'s camera to `kind` (module doc); `framed` says the
/// camera is zline's framing. A camera already of that kind is left.
pub fn set_projection(scene: &mut Scene, kind: ProjectionKind, aspect: f32, framed: bool) {
    let mut camera = scene.camera;
    let back = camera.eye - camera.target;
    let distance = back.length();
    match (kind, camera.projection) {
        (ProjectionKind::Orthographic, Projection::Perspective { fovy_degrees, near, far }) => {
            let height = 2.0 * distance * (fovy_degrees.to_radians() / 2.0).tan();
            camera.projection = Projection::Orthographic { height, near, far };
            if framed {
                if let Some((target, height)) = ortho_fit(scene, &camera, aspect) {
                    let shift = target - camera.target;
                    (camera.target, camera.eye) = (target, camera.eye + shift);
                    camera.projection = Projection::Orthographic { height, near, far };
                }
            }
        }
        (ProjectionKind::Perspective, Projection::Orthographic { height, near, far }) => {
            let fovy = ORTHO_TO_PERSPECTIVE_FOVY;
            let d = height / 2.0 / (fovy.to_radians() / 2.0).tan();
            if d.is_finite() && d > 0.0 {
                camera.eye = camera.target + back.normalize_or(Vec3::Z) * d;
            }
            camera.projection = Projection::Perspective { fovy_degrees: fovy, near, far };
        }
        _ => return,
    }
    crate::view::hug(&mut camera, scene);
    scene.camera = camera;
}

/// The centre and height of the tight orthographic view of `scene`'s
/// vertices along `camera`'s direction, for `aspect`; `None` without a
/// finite vertex.
fn ortho_fit(scene: &Scene, camera: &Camera, aspect: f32) -> Option<(Vec3, f32)> {
    let back = (camera.eye - camera.target).normalize_or(Vec3::Z);
    let right = camera.up.cross(back).normalize_or(back.any_orthonormal_vector());
    let up = back.cross(right);
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for o in &scene.objects {
        for p in &o.mesh.positions {
            let w = o.world_from_object.transform_point3(*p);
            if w.is_finite() {
                for (k, axis) in [right, up, back].iter().enumerate() {
                    (lo[k], hi[k]) = (lo[k].min(w.dot(*axis)), hi[k].max(w.dot(*axis)));
                }
            }
        }
    }
    if lo[0] > hi[0] {
        return None;
    }
    let centre = right * (lo[0] + hi[0]) / 2.0 + up * (lo[1] + hi[1]) / 2.0 + back * (lo[2] + hi[2]) / 2.0;
    let height =
        (hi[1] - lo[1]).max((hi[0] - lo[0]) / aspect.max(f32::MIN_POSITIVE)) * (1.0 + 2.0 * ORTHO_MARGIN);
    Some((centre, if height.is_finite() && height > 0.0 { height } else { 1.0 }))
}

/// Scale of the labels' 8 × 8 glyphs.
const LABEL_SCALE: u32 = 2;
/// Pixels between cells, and around the sheet.
const GUTTER: u32 = 4;
/// The label strip's height under each cell.
const LABEL_HEIGHT: u32 = 8 * LABEL_SCALE + 2 * GUTTER;

/// The cells (a name and an image each, all of one size) in rows of
/// `columns`, each name under its image, on a dark grey ground; empty
/// without cells.
pub fn contact_sheet(cells: &[(String, Image)], columns: usize) -> Image {
    let Some((_, first)) = cells.first() else { return Image::empty() };
    let (w, h) = (first.width, first.height);
    let columns = columns.clamp(1, cells.len()) as u32;
    let rows = (cells.len() as u32).div_ceil(columns);
    let (cell_w, cell_h) = (w + GUTTER, h + LABEL_HEIGHT + GUTTER);
    let width = GUTTER + columns * cell_w;
    let height = GUTTER + rows * cell_h;
    let ground = u32::from_le_bytes([40, 40, 40, 255]);
    let mut sheet =
        Image { width, height, pixels: vec![ground; (width * height) as usize], transparent: false };
    for (i, (name, image)) in cells.iter().enumerate() {
        let (x0, y0) = (GUTTER + (i as u32 % columns) * cell_w, GUTTER + (i as u32 / columns) * cell_h);
        for y in 0..h.min(image.height) {
            for x in 0..w.min(image.width) {
                let [r, g, b] = image.pixel(x, y);
                sheet.pixels[((y0 + y) * width + x0 + x) as usize] = u32::from_le_bytes([r, g, b, 255]);
            }
        }
        let text_w = 8 * LABEL_SCALE * name.chars().count() as u32;
        let tx = x0 + w.saturating_sub(text_w) / 2;
        draw_label(&mut sheet, tx, y0 + h + GUTTER, name);
    }
    sheet
}

/// Draws `text` in white at (x, y), glyphs scaled by [`LABEL_SCALE`];
/// characters outside ASCII as `?`, text past the edge cut.
fn draw_label(image: &mut Image, x: u32, y: u32, text: &str) {
    let white = u32::from_le_bytes([235, 235, 235, 255]);
    for (j, c) in text.chars().enumerate() {
        let glyph = BASIC_LEGACY[if c.is_ascii() { c as usize } else { '?' as usize }];
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8u32 {
                if bits >> col & 1 == 0 {
                    continue;
                }
                for (dy, dx) in (0..LABEL_SCALE).flat_map(|a| (0..LABEL_SCALE).map(move |b| (a, b))) {
                    let px = x + (j as u32 * 8 + col) * LABEL_SCALE + dx;
                    let py = y + row as u32 * LABEL_SCALE + dy;
                    if px < image.width && py < image.height {
                        image.pixels[(py * image.width + px) as usize] = white;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bunny_like() -> Scene {
        // A box twice as tall as wide, half as deep: each view sees a
        // different shape.
        let mesh = zline_scene::cube(1.0);
        let mut scene = zline_io::scene_for_model(vec![mesh], Default::default());
        scene.objects[0].world_from_object = glam::Mat4::from_scale(Vec3::new(1.0, 2.0, 0.5));
        scene.camera = zline_io::model_camera(&scene.objects, 1.0);
        scene.settings.width = 100;
        scene.settings.height = 100;
        scene
    }

    #[test]
    fn each_named_view_looks_along_its_axis_and_frames_the_model() {
        for view in NamedView::ALL {
            let mut scene = bunny_like();
            view.apply(&mut scene, 1.0, true);
            let (back, up) = view.direction();
            let seen = (scene.camera.eye - scene.camera.target).normalize();
            assert!((seen - back).length() < 1e-5, "{}: {seen}", view.name());
            assert_eq!(scene.camera.up, up);
            assert_eq!(NamedView::from_name(view.name()), Some(view));
            // The default key light keeps its place relative to the camera.
            let key = |lights: &[Light]| match lights[0] {
                Light::Directional { direction, .. } => direction,
                _ => panic!("directional"),
            };
            let turned = key(&scene.lights);
            let frame = basis(back, up);
            let framing = basis(zline_io::VIEW_DIRECTION, Vec3::Y);
            let from_front = framing.transpose() * key(&zline_io::default_lights());
            assert!((frame.transpose() * turned - from_front).length() < 1e-5, "{}", view.name());
        }
        assert_eq!(NamedView::from_name("sideways"), None);
    }

    #[test]
    fn an_orthographic_front_view_is_the_tight_box_with_its_margin() {
        let mut scene = bunny_like();
        NamedView::Front.apply(&mut scene, 1.0, true);
        set_projection(&mut scene, ProjectionKind::Orthographic, 1.0, true);
        let Projection::Orthographic { height, near, far } = scene.camera.projection else { panic!("ortho") };
        // Seen from the front the box is 1 wide and 2 tall.
        assert!((height - 2.0 * 1.1).abs() < 1e-5, "{height}");
        assert!(scene.camera.target.length() < 1e-5);
        // The whole box lies between near and far.
        let d = (scene.camera.eye - scene.camera.target).length();
        assert!(near < d - 0.25 && far > d + 0.25, "{near} {far} {d}");
        // And back to perspective at 45°, showing the same height.
        set_projection(&mut scene, ProjectionKind::Perspective, 1.0, false);
        let Projection::Perspective { fovy_degrees, .. } = scene.camera.projection else { panic!("persp") };
        assert_eq!(fovy_degrees, ORTHO_TO_PERSPECTIVE_FOVY);
        let d = (scene.camera.eye - scene.camera.target).length();
        assert!((2.0 * d * (22.5f32).to_radians().tan() - 2.2).abs() < 1e-4);
    }

    #[test]
    fn a_contact_sheet_holds_every_cell_under_its_name() {
        let cell = |v: u8| Image {
            width: 10,
            height: 6,
            pixels: vec![u32::from_le_bytes([v, v, v, 255]); 60],
            transparent: false,
        };
        let cells: Vec<(String, Image)> =
            (0..5).map(|i| (format!("v{i}"), cell(10 * i as u8 + 100))).collect();
        let sheet = contact_sheet(&cells, 3);
        assert_eq!((sheet.width, sheet.height), (GUTTER + 3 * 14, GUTTER + 2 * (6 + LABEL_HEIGHT + GUTTER)));
        // Cell 4 (second row, second column) at its place.
        let (x, y) = (GUTTER + 14 + 5, GUTTER + (6 + LABEL_HEIGHT + GUTTER) + 3);
        assert_eq!(sheet.pixel(x, y), [140, 140, 140]);
        // Its label drew white pixels in the strip below.
        let strip = (GUTTER + 6 + LABEL_HEIGHT + GUTTER + 6)..(2 * (6 + LABEL_HEIGHT + GUTTER));
        assert!(strip.clone().any(|y| (0..sheet.width).any(|x| sheet.pixel(x, y) == [235, 235, 235])));
        assert_eq!(contact_sheet(&[], 3).width, 0);
    }
}
