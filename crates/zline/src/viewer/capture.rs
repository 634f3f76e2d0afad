//! A real screenshot of `zline view`, for scripts and tests: the viewer
//! runs on a private Xvfb server whose screen is a memory-mapped XWD file
//! (`Xvfb -fbdir`), and the screen is read back from the X server's own
//! framebuffer while the window shows its frames.
//!
//! [`under_xvfb`] starts `Xvfb :N -screen 0 WxHx24 -fbdir DIR` on the first
//! free display number from 90, the screen exactly the window's size (an X
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
    let status = loop {
        if let Some(status) = viewer.try_wait()? {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            let _ = viewer.kill();
            let _ = viewer.wait();
            bail!("zline view did not exit within {} s", TIMEOUT.as_secs());
        }
        if let Ok(bytes) = std::fs::read(&screen_file) {
            let screen =
                super::xwd::read(&bytes).map_err(|e| anyhow::anyhow!("{}: {e}", screen_file.display()))?;
            let matching = matching_fraction(&screen, &expected);
            if best.as_ref().is_none_or(|(m, _)| matching > *m) {
                best = Some((matching, screen));
            }
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    server.stop();
    if !status.success() {
        bail!("zline view failed under Xvfb ({status})");
    }
    let (matching, screen) = best.context("the X screen was never readable")?;
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
    /// Starts Xvfb on the first display number from 90 that no running
    /// server holds and waits for its socket. A lock file whose process is
    /// gone (a server killed before it could clean up) does not hold its
    /// number: Xvfb replaces such a stale lock itself.
    fn start(xvfb: &Path, fbdir: &Path, (w, h): (u32, u32)) -> Result<Server> {
        for display in 90..190 {
            let lock = PathBuf::from(format!("/tmp/.X{display}-lock"));
            if lock.exists() && lock_is_live(&lock) {
                continue;
            }
            let mut child = Command::new(xvfb)
                .arg(format!(":{display}"))
                .args(["-screen", "0", &format!("{w}x{h}x24"), "-nolisten", "tcp", "-fbdir"])
                .arg(fbdir)
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .with_context(|| format!("cannot run {}", xvfb.display()))?;
            let socket = PathBuf::from(format!("/tmp/.X11-unix/X{display}"));
            let start = Instant::now();
            while start.elapsed() < Duration::from_secs(10) {
                if child.try_wait()?.is_some() {
                    // Another server took the number first.
                    break;
                }
                if socket.exists() && fbdir.join("Xvfb_screen0").exists() {
                    return Ok(Server { child, display });
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
        bail!("could not start Xvfb on any display from :90 to :189")
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

/// True when the X lock file `lock` names a process that still runs (or
/// cannot be read, which is taken as held).
fn lock_is_live(lock: &Path) -> bool {
    let Ok(text) = std::fs::read_to_string(lock) else { return true };
    match text.trim().parse::<u32>() {
        Ok(pid) => Path::new(&format!("/proc/{pid}")).exists(),
        Err(_) => true,
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.stop();
    }
}
