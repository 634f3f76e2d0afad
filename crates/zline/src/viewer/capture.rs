//! A real screenshot of `zline view`, for scripts and tests: the viewer
//! runs on a private Xvfb server whose screen is a memory-mapped XWD file
//! (`Xvfb -fbdir`), and the screen is read back from the X server's own
//! framebuffer while the window shows its frames.
//!
//! [`under_xvfb`] starts `Xvfb -displayfd 1 -screen 0 WxHx24 -fbdir DIR`,
//! which takes a free display number itself and writes it once it accepts
//! clients, the screen exactly the window's size (an X
//! server without a window manager opens the window centred: here at the
//! origin, covering the screen), runs `zline view … --exit-after-frames N`
//! on it and reads the screen every 20 ms until the viewer exits, keeping
//! the read closest to the frame zline renders itself (its
//! `--save-first-frame`), and stops the server.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use zline_pipeline::Image;

/// How long the viewer may run before the capture gives up.
const TIMEOUT: Duration = Duration::from_secs(120);

/// What a capture saw.
#[derive(Debug)]
pub struct Capture {
    /// The X screen, read from Xvfb's framebuffer.
    pub screen: Image,
    /// The frame zline renders for the same command line, without a window.
    pub expected: Image,
    /// The fraction of the screen's pixels equal to the expected frame's
    /// (the frame-time text covers a few percent).
    pub matching: f64,
}

/// The `Xvfb` program on `PATH`, if any.
pub fn find_xvfb() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).map(|dir| dir.join("Xvfb")).find(|p| p.is_file())
}

/// The fraction of pixels of `a` equal to `b`'s (0 when the sizes differ).
pub fn matching_fraction(a: &Image, b: &Image) -> f64 {
    if (a.width, a.height) != (b.width, b.height) || a.pixels.is_empty() {
        return 0.0;
    }
    let rgb = |p: u32| p & 0x00ff_ffff;
    let same = a.pixels.iter().zip(&b.pixels).filter(|(p, q)| rgb(**p) == rgb(**q)).count();
    same as f64 / a.pixels.len() as f64
}

/// Runs the `zline` binary at `zline` as `zline view ARGS` (ARGS: the
/// input and the look flags, with a `--size WxH` equal to `size`) on a
/// private Xvfb at `xvfb`, and captures the screen. The viewer is asked
/// to exit after `frames` presented frames (it presents its last frame
/// again about every 10 ms while idle).
pub fn under_xvfb(
    xvfb: &Path,
    zline: &Path,
    args: &[OsString],
    size: (u32, u32),
    frames: u64,
) -> Result<Capture> {
    let dir = tempfile::tempdir().context("cannot make a folder for the X screen")?;
    let expected_path = dir.path().join("expected.png");
    let status = Command::new(zline)
        .arg("view")
        .args(args)
        .arg("--save-first-frame")
        .arg(&expected_path)
        .stdout(Stdio::null())
        .status()
        .with_context(|| format!("cannot run {}", zline.display()))?;
    if !status.success() {
        bail!("zline view --save-first-frame failed ({status})");
    }
    let expected = read_png(&expected_path)?;
    let mut server = Server::start(xvfb, dir.path(), size)?;
    let mut viewer = Command::new(zline)
        .arg("view")
        .args(args)
        .arg("--exit-after-frames")
        .arg(frames.to_string())
        .env("DISPLAY", format!(":{}", server.display))
        .stdout(Stdio::null())
        .spawn()
        .with_context(|| format!("cannot run {}", zline.display()))?;
    let screen_file = dir.path().join("Xvfb_screen0");
    let start = Instant::now();
    let mut best: Option<(f64, Image)> = None;
    let mut last_error = None;
    let status = loop {
        if let Some(status) = viewer.try_wait()? {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            let _ = viewer.kill();
            let _ = viewer.wait();
            bail!("zline view did not exit within {} s", TIMEOUT.as_secs());
        }
        // A read may catch the file between the server's writes; such a
        // read is skipped, and named only when no read ever succeeds.
        match std::fs::read(&screen_file).map_err(|e| e.to_string()).and_then(|b| super::xwd::read(&b)) {
            Ok(screen) => {
                let matching = matching_fraction(&screen, &expected);
                if best.as_ref().is_none_or(|(m, _)| matching > *m) {
                    best = Some((matching, screen));
                }
            }
            Err(e) => last_error = Some(e),
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    server.stop();
    if !status.success() {
        bail!("zline view failed under Xvfb ({status})");
    }
    let Some((matching, screen)) = best else {
        bail!(
            "{}: the X screen was never readable ({})",
            screen_file.display(),
            last_error.unwrap_or_default()
        );
    };
    Ok(Capture { screen, expected, matching })
}

fn read_png(path: &Path) -> Result<Image> {
    let rgb = image::open(path).with_context(|| format!("cannot read {}", path.display()))?.to_rgb8();
    let pixels = rgb.pixels().map(|p| u32::from_le_bytes([p[0], p[1], p[2], 0])).collect();
    Ok(Image { width: rgb.width(), height: rgb.height(), pixels, transparent: false })
}

/// A running Xvfb, stopped when dropped.
struct Server {
    child: Child,
    display: u32,
}

impl Server {
    /// Starts Xvfb with `-displayfd`: the server takes the first display
    /// number no other server holds (its own lock files decide, so two
    /// captures at once never share a number) and writes the number to its
    /// standard output, a pipe here, only once its screen exists and it
    /// accepts clients.
    fn start(xvfb: &Path, fbdir: &Path, (w, h): (u32, u32)) -> Result<Server> {
        let (reader, writer) = std::io::pipe().context("cannot make a pipe for Xvfb's display number")?;
        let child = Command::new(xvfb)
            .args(["-displayfd", "1", "-screen", "0", &format!("{w}x{h}x24"), "-nolisten", "tcp", "-fbdir"])
            .arg(fbdir)
            .stdout(writer)
            .stderr(Stdio::null())
            .spawn()
            .with_context(|| format!("cannot run {}", xvfb.display()))?;
        // The server holds the pipe's only writer now: the read ends with
        // the number, or at end of file when the server exits first.
        let mut server = Server { child, display: 0 };
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = std::io::BufRead::read_line(&mut std::io::BufReader::new(reader), &mut line);
            let _ = tx.send(line);
        });
        let line = match rx.recv_timeout(Duration::from_secs(30)) {
            Ok(line) => line,
            Err(_) => bail!("{} did not report a display within 30 s", xvfb.display()),
        };
        match line.trim().parse() {
            Ok(display) => server.display = display,
            Err(_) => bail!("{} exited before it reported a display (-displayfd)", xvfb.display()),
        }
        Ok(server)
    }

    /// Asks the server to end (SIGTERM, so that it removes its lock file
    /// and socket), and kills it when it has not within two seconds.
    fn stop(&mut self) {
        let asked = Command::new("kill").arg(self.child.id().to_string()).stderr(Stdio::null()).status();
        if asked.is_ok_and(|s| s.success()) {
            let start = Instant::now();
            while start.elapsed() < Duration::from_secs(2) {
                if matches!(self.child.try_wait(), Ok(Some(_))) {
                    return;
                }
                std::thread::sleep(Duration::from_millis(10));
            }
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.stop();
    }
}
