//! The viewer's state machine: what `zline view` shows, driven by input
//! events, with no window in sight (the window is `viewer::window`).
//!
//! [`ViewerState`] holds the scene as the command line set it up (the
//! *home* view), the current camera, the settings the keys switch, the
//! window's size and the clock; [`ViewerState::handle`] takes one
//! [`Event`], [`ViewerState::frame_to_render`] says whether a frame is due
//! and at what resolution ([`FrameRequest`]), and [`ViewerState::scene`]
//! gives the scene to render for it.
//!
//! - **Camera**: a left drag orbits about the target ([`ORBIT_DEGREES_PER_PIXEL`]),
//!   a right or middle drag (or shift + left) pans in the view plane so the
//!   point under the target follows the cursor, the wheel zooms by
//!   [`ZOOM_PER_NOTCH`] a notch, clamped to [`MAX_ZOOM`]× either way from
//!   the home view. Orbit and zoom are `crate::view::ViewChange`, the
//!   code of `render`'s camera flags; near and far hug the scene after
//!   every move.
//! - **Frames only when something changed.** Each change bumps a version;
//!   a frame is due when the version shown is older, or when the frame
//!   shown is a preview and the input has been still for [`REFINE_AFTER`].
//! - **Previews while moving.** During motion (a drag or wheel within
//!   [`REFINE_AFTER`]) frames are drawn at 1/`block` of the window's
//!   resolution without supersampling, `block` chosen so that a frame fits
//!   [`FRAME_BUDGET`] at the cost per sample measured on the last frames;
//!   the window scales them up nearest-neighbour. When the input stops, the
//!   full frame follows (full resolution, the chosen supersampling).
//! - **Progressive refinement** ([`ViewerState::refine_progressively`],
//!   for the ray tracer, whose full frame takes seconds): when the input
//!   stops, the block halves frame by frame from the preview's (at least
//!   [`MAX_BLOCK`] for a new view) down to the full frame, so a coarse
//!   picture comes at once and sharpens.

use std::time::Duration;

use glam::Vec3;
use zline_scene::{
    Camera, Fog, Object, Projection, Scene, ShadingMode, ShadowMode, WireframeMode, MAX_SAMPLES, MAX_SSAA,
};

use crate::view::{hug, ViewChange};

/// The longest a preview frame should take.
pub const FRAME_BUDGET: Duration = Duration::from_millis(33);
/// How long the input must be still before the full frame is drawn.
pub const REFINE_AFTER: Duration = Duration::from_millis(150);
/// The coarsest preview: one rendered pixel per `MAX_BLOCK`² window pixels.
pub const MAX_BLOCK: u32 = 8;
/// Orbit speed of a left drag.
pub const ORBIT_DEGREES_PER_PIXEL: f32 = 0.4;
/// Magnification of one wheel notch towards the screen.
pub const ZOOM_PER_NOTCH: f32 = 1.1;
/// The zoom stops at this factor from the home view, in and out.
pub const MAX_ZOOM: f32 = 64.0;
/// How many of the last frames' costs the preview resolution follows.
const COST_HISTORY: usize = 4;

/// A mouse button, as the state machine sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Button {
    /// Orbits (pans with shift).
    Left,
    /// Pans.
    Middle,
    /// Pans.
    Right,
}

pub use super::keys::Action;
pub use super::scene_edits::magnification;
use super::scene_edits::{fitted_fog, truncate, untextured};

/// One input to the state machine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// The mouse moved by (dx, dy) window pixels (y down) with `button`
    /// held; `shift` says whether shift was down.
    Drag {
        /// The button held.
        button: Button,
        /// Window pixels to the right.
        dx: f32,
        /// Window pixels down.
        dy: f32,
        /// Shift held: a left drag pans.
        shift: bool,
    },
    /// The wheel turned by this many notches (positive: away from the
    /// user, zooming in).
    Wheel(f32),
    /// A key's action.
    Key(Action),
    /// A left click (press and release without moving) on window pixel
    /// (x, y): the pixel inspector follows it.
    Click(u32, u32),
    /// The window's drawable area is now this many pixels.
    Resize(u32, u32),
    /// The clock: the time since the viewer started.
    Tick(Duration),
    /// A frame for this request was drawn in this time.
    FrameRendered(FrameRequest, Duration),
}

/// A frame to draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRequest {
    /// Window pixels per rendered pixel along each side (1: full resolution).
    pub block: u32,
    /// The rendered image's width: the window's divided by `block`, rounded up.
    pub width: u32,
    /// The rendered image's height.
    pub height: u32,
    /// Supersampling of the frame.
    pub ssaa: u32,
    /// True for the full frame (full resolution, the chosen supersampling);
    /// false for a preview while the camera moves.
    pub full: bool,
    /// The state's version the frame shows.
    pub version: u64,
}

/// The settings the keys switch; the rest of the scene is as loaded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Toggles {
    /// Shading for objects without their own.
    pub shading: ShadingMode,
    /// Textures drawn.
    pub textures: bool,
    /// Fog drawn.
    pub fog: bool,
    /// Wireframe mode.
    pub wireframe: WireframeMode,
    /// Shadow method.
    pub shadows: ShadowMode,
    /// Supersampling of full frames.
    pub ssaa: u32,
    /// The hidden-surface method.
    pub visibility: zline_scene::Visibility,
    /// Back-face culling as the scene says (false: off everywhere).
    pub culling: bool,
    /// Attribute interpolation.
    pub interpolation: zline_scene::Interpolation,
    /// Step mode: how many triangles are drawn, in draw order (`None`:
    /// all of them).
    pub step: Option<usize>,
    /// The overdraw heat map under this rule instead of the image.
    pub overdraw: Option<zline_raster::TieRule>,
    /// The depth buffer shown instead of the colours.
    pub depth_view: bool,
    /// Each mesh's triangles drawn in a shuffled order.
    pub shuffled: bool,
    /// Step mode: the last triangle drawn only down to this pixel row of
    /// the full frame (`None`: whole).
    pub scanline: Option<u32>,
}

/// The viewer's state (see the module documentation).
#[derive(Clone, Debug)]
pub struct ViewerState {
    /// The scene as the command line set it up, with the home camera.
    home: Scene,
    /// The objects with their diffuse maps removed, made at the first T.
    untextured: Option<Vec<Object>>,
    /// The fog F turns on: the scene's, or one fitted to its bounds.
    fog: Fog,
    camera: Camera,
    toggles: Toggles,
    window: (u32, u32),
    overlay: bool,
    now: Duration,
    /// When the camera last moved (a drag or the wheel).
    moved_at: Option<Duration>,
    version: u64,
    /// The last frame drawn.
    shown: Option<FrameRequest>,
    /// Seconds per sample of the last frames, newest last.
    costs: Vec<f64>,
    screenshot: bool,
    /// The pixel a click asked the inspector to follow, until taken.
    inspect: Option<(u32, u32)>,
    quit: bool,
    /// Halve the block frame by frame when still (module doc).
    progressive: bool,
}

impl ViewerState {
    /// The state for `scene` as the command line set it up (size, camera,
    /// settings); the window starts at the scene's image size.
    pub fn new(scene: Scene) -> ViewerState {
        let s = &scene.settings;
        let toggles = Toggles {
            shading: s.shading,
            textures: true,
            fog: scene.fog.is_some(),
            wireframe: s.wireframe.mode,
            shadows: scene.shadows.mode,
            ssaa: s.ssaa.clamp(1, MAX_SSAA),
            visibility: s.visibility,
            culling: true,
            interpolation: s.interpolation,
            step: None,
            overdraw: None,
            depth_view: false,
            shuffled: false,
            scanline: None,
        };
        let fog = scene.fog.unwrap_or_else(|| fitted_fog(&scene));
        ViewerState {
            untextured: None,
            fog,
            camera: scene.camera,
            toggles,
            window: (s.width.max(1), s.height.max(1)),
            overlay: true,
            now: Duration::ZERO,
            moved_at: None,
            version: 0,
            shown: None,
            costs: Vec::new(),
            screenshot: false,
            inspect: None,
            quit: false,
            progressive: false,
            home: scene,
        }
    }

    /// Takes one event.
    pub fn handle(&mut self, event: Event) {
        match event {
            Event::Drag { button, dx, dy, shift } => {
                if dx == 0.0 && dy == 0.0 || !(dx.is_finite() && dy.is_finite()) {
                    return;
                }
                match (button, shift) {
                    (Button::Left, false) => self.orbit(dx, dy),
                    _ => self.pan(dx, dy),
                }
                self.moved();
            }
            Event::Wheel(notches) => {
                if notches != 0.0 && notches.is_finite() {
                    self.zoom(ZOOM_PER_NOTCH.powf(notches));
                    self.moved();
                }
            }
            Event::Key(action) => self.act(action),
            Event::Click(x, y) => {
                let (w, h) = self.window;
                self.inspect = Some((x.min(w - 1), y.min(h - 1)));
                // The frame is drawn again, with the inspector's line over it.
                self.version += 1;
            }
            Event::Resize(w, h) => {
                let size = (w.max(1), h.max(1));
                if size != self.window {
                    self.window = size;
                    self.toggles.ssaa = self.toggles.ssaa.min(self.max_ssaa());
                    self.version += 1;
                }
            }
            Event::Tick(now) => self.now = self.now.max(now),
            Event::FrameRendered(request, took) => {
                let samples = f64::from(request.width)
                    * f64::from(request.height)
                    * f64::from(request.ssaa * request.ssaa);
                if samples > 0.0 {
                    if self.costs.len() == COST_HISTORY {
                        self.costs.remove(0);
                    }
                    self.costs.push(took.as_secs_f64() / samples);
                }
                self.shown = Some(request);
            }
        }
    }

    /// Refine the picture progressively when the input stops (module doc).
    pub fn refine_progressively(&mut self) {
        self.progressive = true;
    }

    /// The frame due now, if any: nothing changed and the full frame shown
    /// gives `None`.
    pub fn frame_to_render(&self) -> Option<FrameRequest> {
        let moving = self.moving();
        if self.progressive && !moving {
            return match self.shown {
                Some(shown) if shown.version == self.version && shown.full => None,
                Some(shown) if shown.version == self.version => Some(self.finer(shown.block / 2)),
                _ => Some(self.finer(self.preview_request().block.max(MAX_BLOCK))),
            };
        }
        let wanted = if moving { self.preview_request() } else { self.full_request() };
        match self.shown {
            Some(shown) if shown.version == self.version && (shown.full || moving) => None,
            _ => Some(wanted),
        }
    }

    /// The full frame of the current view: full resolution, the chosen
    /// supersampling.
    pub fn full_request(&self) -> FrameRequest {
        self.request(1, self.toggles.ssaa, true)
    }

    /// The scene to render for `request`: the home scene with the current
    /// camera, the toggled settings and the request's size.
    pub fn scene(&self, request: &FrameRequest) -> Scene {
        self.scene_at(request, self.toggles.step)
    }

    /// [`Self::scene`] with the first `step` triangles (all for `None`).
    fn scene_at(&self, request: &FrameRequest, step: Option<usize>) -> Scene {
        let mut scene = self.home.clone();
        scene.camera = self.camera;
        let s = &mut scene.settings;
        (s.width, s.height, s.ssaa) = (request.width, request.height, request.ssaa);
        s.shading = self.toggles.shading;
        s.wireframe.mode = self.toggles.wireframe;
        (s.visibility, s.interpolation) = (self.toggles.visibility, self.toggles.interpolation);
        scene.shadows.mode = self.toggles.shadows;
        scene.fog = self.toggles.fog.then_some(self.fog);
        if !self.toggles.textures {
            if let Some(objects) = &self.untextured {
                scene.objects.clone_from(objects);
            }
        }
        if !self.toggles.culling {
            for object in &mut scene.objects {
                object.cull_back_faces = false;
            }
        }
        if self.toggles.shuffled {
            crate::order::shuffle_triangles(&mut scene, 1);
        }
        truncate(&mut scene, step);
        scene
    }

    /// With a scanline in step mode: the row (in `request`'s pixels) down
    /// to which the last triangle is drawn, and the scene without it; the
    /// frame shows `scene` above and on the row and this one below it
    /// (exact: the z-buffer lets a triangle change only its own samples).
    pub fn scanline_step(&self, request: &FrameRequest) -> Option<(u32, Scene)> {
        let (k, row) = (self.toggles.step?, self.toggles.scanline?);
        Some((row / request.block.max(1), self.scene_at(request, Some(k.saturating_sub(1)))))
    }

    /// The first pixel row the step mode's last triangle can cover, where
    /// `]` starts (0 when it cannot be projected).
    fn last_triangle_top(&self) -> u32 {
        let scene = self.scene(&self.full_request());
        let Some(mut left) = self.toggles.step else { return 0 };
        let aspect = self.window.0 as f32 / self.window.1.max(1) as f32;
        let clip_from_world = scene.camera.clip_from_eye(aspect) * scene.camera.eye_from_world();
        for o in &scene.objects {
            let n = o.mesh.triangles.len();
            if left <= n && left > 0 {
                let t = o.mesh.triangles[left - 1];
                let ys = t.map(|i| {
                    let p = clip_from_world * o.world_from_object * o.mesh.positions[i as usize].extend(1.0);
                    (1.0 - p.y / p.w) / 2.0 * self.window.1 as f32
                });
                let top = ys.iter().copied().fold(f32::INFINITY, f32::min);
                return if top.is_finite() { top.max(0.0) as u32 } else { 0 };
            }
            left = left.saturating_sub(n);
        }
        0
    }

    /// The triangles of the home scene.
    fn triangle_count(&self) -> usize {
        self.home.objects.iter().map(|o| o.mesh.triangles.len()).sum()
    }
}

impl ViewerState {
    /// What the learner should see after the last classroom toggle (Z, C,
    /// I, P), for the overlay; `None` when they are as loaded.
    pub fn hint(&self) -> Option<String> {
        let t = &self.toggles;
        let s = &self.home.settings;
        if let Some(rule) = t.overdraw {
            use zline_raster::TieRule;
            return Some(String::from(match rule {
                TieRule::TopLeft => {
                    "overdraw (O): fragments a pixel, dark blue 1, cyan 2, green 3, yellow 4, red 6"
                }
                TieRule::Closed => {
                    "overdraw without the top-left rule, closed: edges through sample centres drawn twice"
                }
                TieRule::Open => {
                    "overdraw without the top-left rule, open: edges through sample centres drawn by neither"
                }
            }));
        }
        if t.depth_view {
            return Some(
                "depth buffer: eye depth, near white to far dark, nothing black: what the z-buffer compares"
                    .into(),
            );
        }
        if let (Some(n), Some(row)) = (t.step, t.scanline) {
            return Some(format!(
                "step mode: triangle {n} drawn down to scanline {row} (] next row, [ back)"
            ));
        }
        if let Some(n) = t.step {
            return Some(format!(
                "step mode: the first {n} of {} triangles, in draw order (. next, , back, ] by scanline, P off)",
                self.triangle_count()
            ));
        }
        let line = if t.visibility != s.visibility && t.visibility == zline_scene::Visibility::Painter {
            Some("painter: sorted by farthest depth; wrong where triangles interpenetrate or overlap cyclically")
        } else if t.shuffled {
            Some("shuffled order: the same picture with the z-buffer; with the painter's algorithm too (it sorts)")
        } else if !t.culling {
            Some("culling off: a closed model looks the same, more triangles are drawn")
        } else if t.interpolation != s.interpolation
            && t.interpolation == zline_scene::Interpolation::ScreenLinear
        {
            Some("affine: textures swim and bend on triangles seen at an angle")
        } else {
            None
        };
        line.map(String::from)
    }

    /// The current camera.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// The home camera (the command line's; R brings it back).
    pub fn home_camera(&self) -> Camera {
        self.home.camera
    }

    /// The settings the keys switch.
    pub fn toggles(&self) -> Toggles {
        self.toggles
    }

    /// The window's size.
    pub fn window(&self) -> (u32, u32) {
        self.window
    }

    /// Whether the frame-time text is drawn.
    pub fn overlay(&self) -> bool {
        self.overlay
    }

    /// True once Esc or Q asked to close.
    pub fn quit(&self) -> bool {
        self.quit
    }

    /// Once after a click: the pixel the caller runs the inspector on
    /// (the full frame's pixel under the cursor).
    pub fn take_inspection(&mut self) -> Option<(u32, u32)> {
        self.inspect.take()
    }

    /// True once after S: the caller saves the full frame.
    pub fn take_screenshot(&mut self) -> bool {
        std::mem::take(&mut self.screenshot)
    }

    /// The settings in a few words, for the overlay.
    pub fn describe(&self) -> String {
        let t = &self.toggles;
        let shading = match t.shading {
            ShadingMode::Flat => "flat",
            ShadingMode::Gouraud => "gouraud",
            ShadingMode::Phong => "phong",
        };
        let on = |b: bool| if b { "on" } else { "off" };
        format!(
            "{shading}  tex {}  fog {}  wire {}  shadows {}  ssaa {}",
            on(t.textures),
            on(t.fog),
            t.wireframe.name(),
            t.shadows.name(),
            t.ssaa
        )
    }

    fn moving(&self) -> bool {
        self.moved_at.is_some_and(|t| self.now.saturating_sub(t) < REFINE_AFTER)
    }

    fn moved(&mut self) {
        self.moved_at = Some(self.now);
        self.version += 1;
    }

    fn request(&self, block: u32, ssaa: u32, full: bool) -> FrameRequest {
        let (w, h) = self.window;
        FrameRequest {
            block,
            width: w.div_ceil(block),
            height: h.div_ceil(block),
            ssaa,
            full,
            version: self.version,
        }
    }

    /// A refinement step at `block` (the full frame at 1).
    fn finer(&self, block: u32) -> FrameRequest {
        if block <= 1 {
            self.full_request()
        } else {
            self.request(block, 1, false)
        }
    }

    /// A preview: the finest block whose frame fits the budget at the
    /// slowest of the last frames' costs per sample.
    fn preview_request(&self) -> FrameRequest {
        let cost = self.costs.iter().copied().fold(0.0, f64::max);
        let (w, h) = self.window;
        let full = cost * f64::from(w) * f64::from(h);
        let ratio = full / FRAME_BUDGET.as_secs_f64();
        // Blocks of b × b pixels take 1/b² of the time.
        let block = if ratio.is_finite() && ratio > 1.0 { ratio.sqrt().ceil() as u32 } else { 1 };
        self.request(block.clamp(1, MAX_BLOCK), 1, false)
    }

    /// The largest supersampling the window allows within [`MAX_SAMPLES`].
    fn max_ssaa(&self) -> u32 {
        let pixels = u64::from(self.window.0) * u64::from(self.window.1);
        (1..=MAX_SSAA).rev().find(|n| pixels * u64::from(n * n) <= MAX_SAMPLES).unwrap_or(1)
    }

    fn act(&mut self, action: Action) {
        let before = (self.toggles, self.camera);
        match action {
            Action::Shading(mode) => self.toggles.shading = mode,
            Action::ToggleTextures => {
                if self.untextured.is_none() {
                    self.untextured = Some(untextured(&self.home.objects));
                }
                self.toggles.textures = !self.toggles.textures;
            }
            Action::ToggleFog => self.toggles.fog = !self.toggles.fog,
            Action::ToggleVisibility => {
                use zline_scene::Visibility;
                self.toggles.visibility = match self.toggles.visibility {
                    Visibility::ZBuffer => Visibility::Painter,
                    Visibility::Painter => Visibility::ZBuffer,
                }
            }
            Action::ToggleCulling => self.toggles.culling = !self.toggles.culling,
            Action::ToggleStepMode => {
                self.toggles.step = if self.toggles.step.is_some() { None } else { Some(1) };
            }
            Action::StepForward => {
                let all = self.triangle_count();
                self.toggles.step = self.toggles.step.map(|n| (n + 1).min(all));
                self.toggles.scanline = None;
            }
            Action::StepBack => {
                self.toggles.step = self.toggles.step.map(|n| n.saturating_sub(1));
                self.toggles.scanline = None;
            }
            Action::ScanlineForward | Action::ScanlineBack => {
                let last = self.window.1.saturating_sub(1);
                self.toggles.scanline = match (self.toggles.step, self.toggles.scanline, action) {
                    (None | Some(0), ..) => None,
                    (Some(_), None, Action::ScanlineForward) => Some(self.last_triangle_top()),
                    (Some(_), Some(r), Action::ScanlineForward) if r >= last => None,
                    (Some(_), Some(r), Action::ScanlineForward) => Some(r + 1),
                    (Some(_), Some(r), _) => Some(r.saturating_sub(1)),
                    (Some(_), None, _) => Some(last),
                };
            }
            Action::ToggleDepthView => self.toggles.depth_view = !self.toggles.depth_view,
            Action::ToggleShuffle => self.toggles.shuffled = !self.toggles.shuffled,
            Action::CycleOverdraw => {
                use zline_raster::TieRule;
                self.toggles.overdraw = match self.toggles.overdraw {
                    None => Some(TieRule::TopLeft),
                    Some(TieRule::TopLeft) => Some(TieRule::Closed),
                    Some(TieRule::Closed) => Some(TieRule::Open),
                    Some(TieRule::Open) => None,
                };
            }
            Action::ToggleInterpolation => {
                use zline_scene::Interpolation;
                self.toggles.interpolation = match self.toggles.interpolation {
                    Interpolation::PerspectiveCorrect => Interpolation::ScreenLinear,
                    Interpolation::ScreenLinear => Interpolation::PerspectiveCorrect,
                }
            }
            Action::CycleWireframe => {
                self.toggles.wireframe = match self.toggles.wireframe {
                    WireframeMode::None => WireframeMode::All,
                    WireframeMode::All => WireframeMode::HiddenRemoved,
                    WireframeMode::HiddenRemoved => WireframeMode::HiddenDashed,
                    WireframeMode::HiddenDashed => WireframeMode::None,
                }
            }
            Action::CycleShadows => {
                let planes = !self.home.shadows.planes.is_empty();
                self.toggles.shadows = match self.toggles.shadows {
                    ShadowMode::None if planes => ShadowMode::Planar,
                    ShadowMode::None | ShadowMode::Planar => ShadowMode::Map,
                    ShadowMode::Map => ShadowMode::None,
                }
            }
            Action::MoreSamples => self.toggles.ssaa = (self.toggles.ssaa + 1).min(self.max_ssaa()),
            Action::FewerSamples => self.toggles.ssaa = self.toggles.ssaa.saturating_sub(1).max(1),
            Action::ResetCamera => {
                self.camera = self.home.camera;
                self.moved_at = None;
            }
            Action::ToggleOverlay => {
                self.overlay = !self.overlay;
                // The overlay is drawn over the frame: the frame is drawn again.
                self.version += 1;
            }
            Action::Screenshot => self.screenshot = true,
            Action::Quit => self.quit = true,
        }
        if (self.toggles, self.camera) != before {
            self.version += 1;
        }
    }

    /// The home scene with the current camera, for `ViewChange` and `hug`.
    fn with_camera(&self) -> Scene {
        Scene { camera: self.camera, ..self.home.clone() }
    }

    fn aspect(&self) -> f32 {
        self.window.0 as f32 / self.window.1 as f32
    }

    fn orbit(&mut self, dx: f32, dy: f32) {
        let change = ViewChange {
            azimuth: Some(-dx * ORBIT_DEGREES_PER_PIXEL),
            elevation: Some(dy * ORBIT_DEGREES_PER_PIXEL),
            ..ViewChange::default()
        };
        let mut scene = self.with_camera();
        change.apply(&mut scene, self.aspect(), false);
        self.camera = scene.camera;
    }

    /// Moves eye and target in the view plane: the point at the target's
    /// depth under the cursor stays under it.
    fn pan(&mut self, dx: f32, dy: f32) {
        let c = &mut self.camera;
        let forward = (c.target - c.eye).normalize_or(Vec3::NEG_Z);
        let right = forward.cross(c.up).normalize_or(Vec3::X);
        let up = right.cross(forward);
        let view_height = match c.projection {
            Projection::Perspective { fovy_degrees, .. } => {
                2.0 * (c.target - c.eye).length() * (fovy_degrees.to_radians() / 2.0).tan()
            }
            Projection::Orthographic { height, .. } => height,
            Projection::Frustum { bottom, top, near, .. } => {
                (c.target - c.eye).length() * (top - bottom) / near
            }
        };
        let per_pixel = view_height / self.window.1 as f32;
        let shift = (-right * dx + up * dy) * per_pixel;
        if shift.is_finite() {
            c.eye += shift;
            c.target += shift;
        }
        let scene = self.with_camera();
        hug(&mut self.camera, &scene);
    }

    /// Magnifies by `factor`, within [`MAX_ZOOM`] of the home view.
    fn zoom(&mut self, factor: f32) {
        let now = magnification(&self.camera, &self.home.camera);
        let clamped = (now * factor).clamp(1.0 / MAX_ZOOM, MAX_ZOOM) / now;
        if !clamped.is_finite() || clamped == 1.0 {
            return;
        }
        let mut scene = self.with_camera();
        ViewChange { zoom: Some(clamped), ..ViewChange::default() }.apply(&mut scene, self.aspect(), false);
        self.camera = scene.camera;
    }
}
