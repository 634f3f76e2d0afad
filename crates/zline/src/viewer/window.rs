//! The window of `zline view`: minifb on X11, with libX11 loaded when the
//! window opens (nothing is linked at build time, and no other command
//! touches a display). It turns mouse and keys into `viewer::state`
//! events, renders the frames the state asks for and presents them.
//!
//! The loop polls input about every 10 ms and sleeps in between when no
//! frame is due: an idle viewer renders nothing. Frames are drawn on the
//! caller's rayon pool while the loop waits; a preview is scaled up into a
//! window-sized buffer (`viewer::overlay`), the frame time drawn over it,
//! and the buffer handed to the X server.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::time::{Duration, Instant};

use anyhow::{anyhow, Context, Result};
use minifb::{InputCallback, Key, MouseButton, MouseMode, ScaleMode, UseGPU, Window, WindowOptions};
use zline_pipeline::{Image, RenderOptions, Renderer};
use zline_scene::{Scene, ShadingMode};

use super::overlay::{draw_text, upscale};
use super::state::{Action, Button, Event, FrameRequest, ViewerState};

/// How `zline view` runs its window.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    /// The window title's first part (the input's name).
    pub title: String,
    /// S saves to this path with a number added: `view.png` gives
    /// `view-1.png`, `view-2.png`, … (the first free name).
    pub screenshot: PathBuf,
    /// Close after this many frames were presented (frames are presented
    /// again while idle when this is set), for scripts and tests.
    pub exit_after_frames: Option<u64>,
    /// The renderer's options.
    pub render: RenderOptions,
    /// Print a line per frame drawn to stderr (`--timings`): its size,
    /// whether it is a preview, and its time.
    pub timings: bool,
    /// Ray-trace the frames with these options instead of rasterizing
    /// them (the state should then refine progressively).
    pub trace: Option<zline_scene::trace_options::TraceOptions>,
}

/// The keys and what they do, as `zline view --help` lists them.
pub fn action_for(key: Key) -> Option<Action> {
    Some(match key {
        Key::Key1 | Key::NumPad1 => Action::Shading(ShadingMode::Flat),
        Key::Key2 | Key::NumPad2 => Action::Shading(ShadingMode::Gouraud),
        Key::Key3 | Key::NumPad3 => Action::Shading(ShadingMode::Phong),
        Key::T => Action::ToggleTextures,
        Key::F => Action::ToggleFog,
        Key::W => Action::CycleWireframe,
        Key::M => Action::CycleShadows,
        Key::Equal | Key::NumPadPlus => Action::MoreSamples,
        Key::Minus | Key::NumPadMinus => Action::FewerSamples,
        Key::R => Action::ResetCamera,
        Key::H => Action::ToggleOverlay,
        Key::Z => Action::ToggleVisibility,
        Key::C => Action::ToggleCulling,
        Key::I => Action::ToggleInterpolation,
        Key::P => Action::ToggleStepMode,
        Key::Period => Action::StepForward,
        Key::Comma => Action::StepBack,
        Key::O => Action::CycleOverdraw,
        Key::D => Action::ToggleDepthView,
        Key::X => Action::ToggleShuffle,
        Key::RightBracket => Action::ScanlineForward,
        Key::LeftBracket => Action::ScanlineBack,
        Key::S => Action::Screenshot,
        Key::Escape | Key::Q => Action::Quit,
        _ => return None,
    })
}

/// Opens the window at the state's size and runs until it is closed, Esc
/// or Q is pressed, or `exit_after_frames` frames were presented. Fails
/// when no window can be opened (no X display); a screenshot that cannot
/// be written is an `error:` line on stderr, and the window stays.
pub fn run(state: &mut ViewerState, options: &ViewOptions, pool: &rayon::ThreadPool) -> Result<()> {
    let (w, h) = state.window();
    let mut window = Window::new(
        &format!("{} — zline view", options.title),
        w as usize,
        h as usize,
        WindowOptions {
            resize: true,
            scale_mode: ScaleMode::UpperLeft,
            use_gpu: UseGPU::Disabled,
            ..Default::default()
        },
    )
    .map_err(|e| {
        let display = std::env::var("DISPLAY").unwrap_or_else(|_| "unset".into());
        anyhow!("cannot open a window (DISPLAY={display}): {e}; `zline view` needs an X server (or XWayland)")
    })?;
    // The loop paces itself.
    window.set_target_fps(0);
    let presses = Presses::default();
    window.set_input_callback(Box::new(presses.clone()));
    let mut frames = Frames {
        renderer: Renderer::default(),
        image: Image::empty(),
        buffer: Vec::new(),
        presented: 0,
        inspected: None,
    };
    let mut click = Click::default();
    let start = Instant::now();
    let mut mouse: Option<(f32, f32)> = None;
    let mut last_time: Option<Duration> = None;
    while window.is_open() && !state.quit() {
        // The clock first: input events are stamped with it.
        state.handle(Event::Tick(start.elapsed()));
        input(&window, state, (&mut mouse, &mut click), &presses);
        if let Some(pixel) = state.take_inspection() {
            frames.inspected = Some((pixel, inspect(state, options, pool, &mut frames.renderer, pixel)));
        }
        if state.take_screenshot() {
            // A failed save is reported; the window stays.
            match screenshot(state, options, pool, &mut frames.renderer) {
                Ok(path) => println!("saved {}", path.display()),
                Err(e) => eprintln!("error: {}", crate::error_line(&e)),
            }
        }
        let size = window.get_size();
        if let Some(request) = state.frame_to_render() {
            let took = frames.render(state, &request, options, pool);
            state.handle(Event::FrameRendered(request, took));
            last_time = Some(took);
            if options.timings {
                eprintln!("{}", frame_line(&request, took));
            }
            frames.compose(state, &request, size, took);
            window.set_title(&title(&options.title, took));
            frames.present(&mut window, size)?;
        } else if options.exit_after_frames.is_some() && last_time.is_some() {
            // Scripts wait for frames: present the last one again.
            std::thread::sleep(Duration::from_millis(10));
            frames.present(&mut window, size)?;
        } else {
            std::thread::sleep(Duration::from_millis(10));
            window.update();
        }
        if options.exit_after_frames.is_some_and(|n| frames.presented >= n) {
            break;
        }
    }
    Ok(())
}

/// The renderer's buffers from frame to frame.
struct Frames {
    renderer: Renderer,
    image: Image,
    buffer: Vec<u32>,
    presented: u64,
    /// The last click's pixel and summary, over the frame.
    inspected: Option<((u32, u32), String)>,
}

impl Frames {
    fn render(
        &mut self,
        state: &ViewerState,
        request: &FrameRequest,
        options: &ViewOptions,
        pool: &rayon::ThreadPool,
    ) -> Duration {
        let scene = state.scene(request);
        let t = Instant::now();
        let how = (&options.render, options.trace.as_ref());
        draw((&scene, state.toggles()), how, pool, &mut self.renderer, &mut self.image);
        if let Some((row, previous)) = state.scanline_step(request) {
            let mut below = Image::empty();
            draw((&previous, state.toggles()), how, pool, &mut self.renderer, &mut below);
            scanline_compose(&mut self.image, &below, row);
        }
        t.elapsed()
    }

    /// The window's pixels: the frame scaled up, the overlay over it.
    fn compose(
        &mut self,
        state: &ViewerState,
        request: &FrameRequest,
        (w, h): (usize, usize),
        took: Duration,
    ) {
        upscale(&self.image, request.block, w, h, &mut self.buffer);
        if let Some(row) = state.toggles().scanline.filter(|_| state.toggles().step.is_some()) {
            // The scanline reached, as a red line.
            let y = row as usize;
            if y < h {
                self.buffer[y * w..(y + 1) * w].iter_mut().step_by(2).for_each(|p| *p = 0x00ff_3030);
            }
        }
        if let Some(((x, y), _)) = self.inspected {
            // A yellow cross around the inspected pixel, the pixel left shown.
            for d in 2..6i64 {
                for (dx, dy) in [(d, 0), (-d, 0), (0, d), (0, -d)] {
                    let (px, py) = (i64::from(x) + dx, i64::from(y) + dy);
                    if (0..w as i64).contains(&px) && (0..h as i64).contains(&py) {
                        self.buffer[py as usize * w + px as usize] = 0x00ff_e040;
                    }
                }
            }
        }
        if state.overlay() {
            let ms = took.as_secs_f64() * 1e3;
            let resolution = if request.block == 1 {
                format!("{}x{}", request.width, request.height)
            } else {
                format!("{}x{} (1/{})", request.width, request.height, request.block)
            };
            let first = format!("{ms:.1} ms  {:.0} fps  {resolution}", 1e3 / ms.max(1e-3));
            let (describe, hint) = (state.describe(), state.hint());
            let mut lines = vec![first.as_str(), describe.as_str()];
            lines.extend(hint.as_deref());
            lines.extend(self.inspected.as_ref().map(|(_, line)| line.as_str()));
            draw_text(&mut self.buffer, w, &lines);
        }
    }

    fn present(&mut self, window: &mut Window, (w, h): (usize, usize)) -> Result<()> {
        if self.buffer.len() != w * h {
            // Resized since the frame was composed: the next frame fits.
            window.update();
            return Ok(());
        }
        window
            .update_with_buffer(&self.buffer, w, h)
            .map_err(|e| anyhow!("cannot draw in the window: {e}"))?;
        self.presented += 1;
        Ok(())
    }
}

/// A `--timings` line: `full 640x480 ssaa 2: 12.3 ms` or
/// `preview 320x240 (1/2): 4.1 ms`.
pub fn frame_line(request: &FrameRequest, took: Duration) -> String {
    let ms = took.as_secs_f64() * 1e3;
    if request.full {
        format!("full {}x{} ssaa {}: {ms:.1} ms", request.width, request.height, request.ssaa)
    } else {
        format!("preview {}x{} (1/{}): {ms:.1} ms", request.width, request.height, request.block)
    }
}

/// The window title: the input and the last frame's time.
fn title(name: &str, took: Duration) -> String {
    let ms = took.as_secs_f64() * 1e3;
    format!("{name} — {ms:.1} ms ({:.0} fps) — zline view", 1e3 / ms.max(1e-3))
}

/// The keys pressed since the last poll, in order, as the X events came:
/// a press and its release within one poll (a quick tap, or a script's)
/// still counts, and a held key's auto-repeat does not.
#[derive(Clone, Default)]
struct Presses {
    keys: Rc<RefCell<(Vec<Key>, Vec<Key>)>>,
}

impl Presses {
    /// The presses since the last call.
    fn take(&self) -> Vec<Key> {
        std::mem::take(&mut self.keys.borrow_mut().0)
    }
}

impl InputCallback for Presses {
    fn add_char(&mut self, _: u32) {}

    fn set_key_state(&mut self, key: Key, down: bool) {
        let (pressed, held) = &mut *self.keys.borrow_mut();
        if !down {
            held.retain(|k| *k != key);
        } else if !held.contains(&key) {
            held.push(key);
            pressed.push(key);
        }
    }
}

/// The step mode's frame at a scanline: `image` (the last triangle drawn)
/// on rows up to `row`, `below` (without it) under them. Exact: the
/// z-buffer lets a triangle change only the samples it covers.
pub fn scanline_compose(image: &mut Image, below: &Image, row: u32) {
    if below.width != image.width || below.height != image.height {
        return;
    }
    let start = (row as usize + 1) * image.width as usize;
    if start < image.pixels.len() {
        image.pixels[start..].copy_from_slice(&below.pixels[start..]);
    }
}

/// A left press followed from its start: released where it began, it is a
/// click.
#[derive(Default)]
struct Click {
    start: Option<(f32, f32)>,
    moved: bool,
}

/// Runs the pixel inspector on the full frame's `pixel`: the report on
/// stdout, a line for the overlay returned.
fn inspect(
    state: &ViewerState,
    options: &ViewOptions,
    pool: &rayon::ThreadPool,
    renderer: &mut Renderer,
    pixel: (u32, u32),
) -> String {
    let scene = state.scene(&state.full_request());
    let mut image = Image::empty();
    match pool.install(|| renderer.inspect(&scene, &options.render, pixel, &mut image)) {
        Ok(trace) => {
            println!("{}", crate::inspect::text(&trace, &scene).trim_end());
            let fragments: usize = trace.samples.iter().map(|s| s.fragments.len()).sum();
            let last = trace.samples.iter().flat_map(|s| s.fragments.last()).last();
            let what = last.map_or_else(
                || "background".to_string(),
                |f| format!("obj {} tri {}", f.object, f.triangle.map_or("?".into(), |t| t.to_string())),
            );
            let [r, g, b, _] = trace.resolved;
            let s = if fragments == 1 { "" } else { "s" };
            format!("inspect ({},{}): {fragments} fragment{s}, {what} = {r} {g} {b}", pixel.0, pixel.1)
        }
        Err(e) => format!("inspect: {e}"),
    }
}

/// Mouse and keys since the last poll, as events.
fn input(
    window: &Window,
    state: &mut ViewerState,
    (mouse, click): (&mut Option<(f32, f32)>, &mut Click),
    presses: &Presses,
) {
    let (w, h) = window.get_size();
    state.handle(Event::Resize(w as u32, h as u32));
    let position = window.get_mouse_pos(MouseMode::Pass);
    let button = if window.get_mouse_down(MouseButton::Left) {
        Some(Button::Left)
    } else if window.get_mouse_down(MouseButton::Right) {
        Some(Button::Right)
    } else if window.get_mouse_down(MouseButton::Middle) {
        Some(Button::Middle)
    } else {
        None
    };
    let shift = window.is_key_down(Key::LeftShift) || window.is_key_down(Key::RightShift);
    if let (Some(button), Some((x, y)), Some((x0, y0))) = (button, position, *mouse) {
        state.handle(Event::Drag { button, dx: x - x0, dy: y - y0, shift });
    }
    *mouse = position;
    // A left press released where it started (within 2 pixels) is a click.
    match (button, click.start, position) {
        (Some(Button::Left), None, Some(p)) if !shift => *click = Click { start: Some(p), moved: false },
        (Some(Button::Left), Some((x0, y0)), Some((x, y))) => {
            click.moved |= (x - x0).abs().max((y - y0).abs()) > 2.0
        }
        (None, Some((x, y)), _) => {
            if !click.moved && x >= 0.0 && y >= 0.0 {
                state.handle(Event::Click(x as u32, y as u32));
            }
            *click = Click::default();
        }
        _ => {}
    }
    if let Some((_, notches)) = window.get_scroll_wheel() {
        state.handle(Event::Wheel(notches));
    }
    for key in presses.take() {
        if let Some(action) = action_for(key) {
            state.handle(Event::Key(action));
        }
    }
}

/// Draws `scene` into `image`: rasterized, or ray-traced when the options
/// say so, or the overdraw heat map or the depth buffer when the toggles
/// ask.
pub fn draw(
    (scene, toggles): (&Scene, crate::viewer::state::Toggles),
    (options, trace): (&RenderOptions, Option<&zline_scene::trace_options::TraceOptions>),
    pool: &rayon::ThreadPool,
    renderer: &mut Renderer,
    image: &mut Image,
) {
    if let Some(rule) = toggles.overdraw {
        let mut counts = zline_pipeline::Overdraw::default();
        pool.install(|| renderer.render_overdraw_into(scene, options, rule, &mut counts));
        *image = crate::layers::overdraw_heat_map(&counts);
        return;
    }
    if toggles.depth_view {
        let mut depth = zline_pipeline::DepthImage::default();
        pool.install(|| renderer.render_with_depth(scene, options, image, &mut depth));
        *image = crate::layers::depth_as_image(&depth);
        return;
    }
    match trace {
        Some(trace) => *image = pool.install(|| crate::ray_traced_image(scene, trace)).0,
        None => {
            pool.install(|| renderer.render_into(scene, options, image));
        }
    }
}

/// Renders the full frame of the current view and writes it to the first
/// free numbered name.
fn screenshot(
    state: &ViewerState,
    options: &ViewOptions,
    pool: &rayon::ThreadPool,
    renderer: &mut Renderer,
) -> Result<PathBuf> {
    let path = numbered(&options.screenshot);
    let scene = state.scene(&state.full_request());
    let mut image = Image::empty();
    draw((&scene, state.toggles()), (&options.render, options.trace.as_ref()), pool, renderer, &mut image);
    crate::save_image(&image, &path)
        .with_context(|| format!("{}: cannot write the screenshot", path.display()))?;
    Ok(path)
}

/// `base` with `-1`, `-2`, … before its extension: the first that does not
/// exist.
pub fn numbered(base: &Path) -> PathBuf {
    let stem = base.file_stem().map_or_else(|| "zline-view".into(), |s| s.to_string_lossy().into_owned());
    let ext = base.extension().map_or_else(|| "png".into(), |e| e.to_string_lossy().into_owned());
    (1u64..)
        .map(|n| base.with_file_name(format!("{stem}-{n}.{ext}")))
        .find(|p| !p.exists())
        .expect("some number is free")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_action_has_its_key() {
        let keys = [
            (Key::Key1, Action::Shading(ShadingMode::Flat)),
            (Key::Key2, Action::Shading(ShadingMode::Gouraud)),
            (Key::Key3, Action::Shading(ShadingMode::Phong)),
            (Key::T, Action::ToggleTextures),
            (Key::F, Action::ToggleFog),
            (Key::W, Action::CycleWireframe),
            (Key::M, Action::CycleShadows),
            (Key::Equal, Action::MoreSamples),
            (Key::NumPadPlus, Action::MoreSamples),
            (Key::Minus, Action::FewerSamples),
            (Key::R, Action::ResetCamera),
            (Key::H, Action::ToggleOverlay),
            (Key::Z, Action::ToggleVisibility),
            (Key::C, Action::ToggleCulling),
            (Key::I, Action::ToggleInterpolation),
            (Key::P, Action::ToggleStepMode),
            (Key::Period, Action::StepForward),
            (Key::Comma, Action::StepBack),
            (Key::O, Action::CycleOverdraw),
            (Key::D, Action::ToggleDepthView),
            (Key::X, Action::ToggleShuffle),
            (Key::RightBracket, Action::ScanlineForward),
            (Key::LeftBracket, Action::ScanlineBack),
            (Key::S, Action::Screenshot),
            (Key::Escape, Action::Quit),
            (Key::Q, Action::Quit),
        ];
        for (key, action) in keys {
            assert_eq!(action_for(key), Some(action), "{key:?}");
        }
        assert_eq!(action_for(Key::Space), None);
    }

    #[test]
    fn a_quick_tap_counts_once_and_auto_repeat_not_at_all() {
        let mut presses = Presses::default();
        // Press and release within one poll; then a held key repeating.
        presses.set_key_state(Key::S, true);
        presses.set_key_state(Key::S, false);
        presses.set_key_state(Key::W, true);
        presses.set_key_state(Key::W, true);
        assert_eq!(presses.take(), vec![Key::S, Key::W]);
        presses.set_key_state(Key::W, true);
        assert_eq!(presses.take(), vec![]);
        presses.set_key_state(Key::W, false);
        presses.set_key_state(Key::W, true);
        assert_eq!(presses.take(), vec![Key::W]);
    }

    #[test]
    fn screenshots_take_the_first_free_number() {
        let dir = tempfile::tempdir().unwrap();
        let base = dir.path().join("shot.png");
        assert_eq!(numbered(&base), dir.path().join("shot-1.png"));
        std::fs::write(dir.path().join("shot-1.png"), b"").unwrap();
        std::fs::write(dir.path().join("shot-2.png"), b"").unwrap();
        assert_eq!(numbered(&base), dir.path().join("shot-3.png"));
        assert_eq!(numbered(&dir.path().join("x.jpg")), dir.path().join("x-1.jpg"));
    }

    #[test]
    fn a_timings_line_says_preview_or_full() {
        let request =
            |block, full| FrameRequest { block, width: 400, height: 300, ssaa: 2, full, version: 0 };
        let ms = Duration::from_micros(16_250);
        assert_eq!(frame_line(&request(2, false), ms), "preview 400x300 (1/2): 16.2 ms");
        assert_eq!(frame_line(&request(1, true), ms), "full 400x300 ssaa 2: 16.2 ms");
    }
}
