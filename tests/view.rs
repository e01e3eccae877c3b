//! The viewer: each demo's window, read back after N frames, against the headless rendering of
//! frame N; and the one-line errors without a display.
//!
//! Each test starts its own X server (`Xvfb`, on a display number it picks itself, stopped
//! when the test ends), so `cargo test` needs no outer `xvfb-run`. Without the `Xvfb` binary
//! the tests fail and say to install the `xvfb` package. The window's context is glutin's (GLX on Xvfb, Mesa
//! llvmpipe; `GALLIUM_DRIVER=softpipe` runs both sides on softpipe), the headless one is the
//! crate's EGL context, so the comparison checks that the window shows the frame the headless
//! code draws.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The tolerance, per colour channel of every pixel: both sides run the same Mesa rasterizer on
/// the same commands into an RGBA8 target, so they should agree exactly; 2/255 leaves room for
/// a window configuration that dithers or rounds differently, and at most 0.1% of the pixels
/// may differ at all.
const MAX_CHANNEL_DIFF: u8 = 2;
const MAX_DIFFERING_FRACTION: f64 = 0.001;

/// An X server of our own, stopped on drop.
struct Xvfb {
    child: Child,
    display: String,
}

impl Xvfb {
    /// Start Xvfb on a display number it picks itself (`-displayfd`): the server tries numbers
    /// from :0 up and keeps the first it can listen on, so parallel tests never take the same
    /// one, and stale `/tmp/.X*-lock` files and sockets left by killed servers do not use the
    /// numbers up (with both planted at :0, it took :0).
    fn start() -> Xvfb {
        let mut child = match Command::new("Xvfb")
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
        {
            Ok(child) => child,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => panic!(
                "the viewer tests need an X server: the Xvfb binary is missing; install the \
                 xvfb package (apt-get install xvfb)"
            ),
            Err(e) => panic!("starting Xvfb: {e}"),
        };
        // Xvfb writes the number once it accepts connections; EOF means it exited.
        let stdout = child.stdout.take().expect("piped stdout");
        let (sender, receiver) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(stdout).read_line(&mut line);
            let _ = sender.send(line);
        });
        let line = receiver
            .recv_timeout(Duration::from_secs(60))
            .unwrap_or_default();
        let server = Xvfb {
            child,
            display: format!(":{}", line.trim()),
        };
        if line.trim().parse::<u32>().is_err() {
            drop(server);
            panic!("Xvfb did not report a display number within 60 s (it printed {line:?})");
        }
        server
    }
}

impl Drop for Xvfb {
    /// SIGTERM, so the server removes its lock file and socket; SIGKILL if it lingers.
    fn drop(&mut self) {
        let _ = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status();
        let start = Instant::now();
        while start.elapsed() < Duration::from_secs(5) {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn viewer(args: &[&str], display: Option<&str>) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"));
    command.arg("view").args(args).env_remove("WAYLAND_DISPLAY");
    match display {
        Some(d) => command.env("DISPLAY", d),
        None => command.env_remove("DISPLAY"),
    };
    command.output().expect("the binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-view-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

/// Run `demo` for `frames` frames in a window on a fresh Xvfb and headless; compare the images.
fn window_matches_headless(name: &str, demo: &[&str], frames: usize) {
    let server = Xvfb::start();
    let frames = frames.to_string();
    let window_png = scratch(&format!("{name}-window.png"));
    let headless_png = scratch(&format!("{name}-headless.png"));
    let common = ["--size", "256x192", "--frames", &frames];
    let run = |png: &Path, headless: bool| {
        let mut args: Vec<&str> = demo.to_vec();
        args.extend(common);
        args.extend(["--screenshot", png.to_str().unwrap()]);
        if headless {
            args.push("--headless");
        }
        let out = viewer(&args, Some(&server.display));
        assert!(
            out.status.success(),
            "view {args:?} failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let window_log = run(&window_png, false);
    assert!(
        window_log.contains("via window"),
        "the window run should name its window context: {window_log}"
    );
    run(&headless_png, true);
    let window = image::open(&window_png).unwrap().to_rgba8();
    let headless = image::open(&headless_png).unwrap().to_rgba8();
    assert_eq!(window.dimensions(), (256, 192), "{name}: window image size");
    assert_eq!(window.dimensions(), headless.dimensions());
    // A frame that is not blank: the demo drew something, with text over it.
    let mut colours: Vec<[u8; 4]> = window.pixels().map(|p| p.0).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(
        colours.len() >= 4,
        "{name}: the window shows only {} colours",
        colours.len()
    );
    let mut worst = 0u8;
    let mut differing = 0usize;
    for (a, b) in window.pixels().zip(headless.pixels()) {
        let d = (0..3).map(|c| a.0[c].abs_diff(b.0[c])).max().unwrap();
        worst = worst.max(d);
        differing += (d > 0) as usize;
    }
    let fraction = differing as f64 / (256.0 * 192.0);
    assert!(
        worst <= MAX_CHANNEL_DIFF && fraction <= MAX_DIFFERING_FRACTION,
        "{name}: window and headless frame {frames} differ: largest channel difference {worst} \
         (at most {MAX_CHANNEL_DIFF}), {differing} pixels differ ({:.3}%, at most {:.1}%); \
         images in {} and {}",
        fraction * 100.0,
        MAX_DIFFERING_FRACTION * 100.0,
        window_png.display(),
        headless_png.display()
    );
}

#[test]
fn collide_scene_window_matches_headless() {
    window_matches_headless(
        "collide-scene",
        &["collide-scene", "touching-tori", "--triangles", "300"],
        3,
    );
}

#[test]
fn collide_scene_buffer_inset_window_matches_headless() {
    // The second buffer (P0) full size, with the help text over it.
    window_matches_headless(
        "collide-p0",
        &[
            "collide-scene",
            "interlocking-tori",
            "--triangles",
            "300",
            "--buffer",
            "1",
            "--help-overlay",
        ],
        2,
    );
}

#[test]
fn without_a_display_the_viewer_names_what_is_missing_and_the_headless_command() {
    let out = viewer(&["collide-scene", "touching-tori", "--frames", "1"], None);
    assert!(!out.status.success(), "no display must be an error");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.trim().lines().count(), 1, "one line: {stderr}");
    assert!(
        stderr.contains("DISPLAY") && stderr.contains("--headless"),
        "names the missing display and the headless command: {stderr}"
    );
    assert!(
        !stderr.contains("panicked"),
        "an error, not a panic: {stderr}"
    );
}

#[test]
fn screenshot_is_not_overwritten_without_force() {
    let path = scratch("exists.png");
    std::fs::write(&path, b"keep").unwrap();
    let p = path.to_str().unwrap();
    let args = [
        "collide-scene",
        "touching-tori",
        "--triangles",
        "300",
        "--frames",
        "1",
        "--headless",
        "--screenshot",
        p,
    ];
    let out = viewer(&args, None);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--force"));
    assert_eq!(std::fs::read(&path).unwrap(), b"keep");
    let mut forced = args.to_vec();
    forced.push("--force");
    let out = viewer(&forced, None);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(image::open(&path).is_ok());
}

#[test]
fn unknown_scene_is_an_error_naming_the_scenes() {
    let out = viewer(
        &[
            "collide-scene",
            "no-such-scene",
            "--frames",
            "1",
            "--headless",
            "--screenshot",
            scratch("none.png").to_str().unwrap(),
        ],
        None,
    );
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("touching-tori"), "{stderr}");
}

#[test]
fn mass_window_matches_headless() {
    window_matches_headless("mass", &["mass", "torus", "--resolution", "32"], 3);
}

#[test]
fn mass_peel_layers_window_matches_headless() {
    window_matches_headless(
        "mass-peels",
        &["mass", "cube", "--resolution", "32", "--buffer", "1"],
        2,
    );
}

#[test]
fn buoyancy_window_matches_headless() {
    window_matches_headless(
        "buoyancy",
        &["buoyancy", "--bodies", "6", "--resolution", "16"],
        3,
    );
}

#[test]
fn crowd_two_pass_window_matches_headless() {
    window_matches_headless("crowd", &["crowd", "--characters", "24"], 3);
}

#[test]
fn crowd_vertex_shader_lod_colours_window_matches_headless() {
    window_matches_headless(
        "crowd-vs",
        &["crowd", "--characters", "24", "--keys", "mc"],
        2,
    );
}

#[test]
fn a_key_the_demo_lacks_is_an_error_listing_its_keys() {
    let out = viewer(
        &[
            "crowd",
            "--characters",
            "4",
            "--keys",
            "q",
            "--frames",
            "1",
            "--headless",
            "--screenshot",
            scratch("keys.png").to_str().unwrap(),
        ],
        None,
    );
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("'q'") && stderr.contains("m, c"),
        "{stderr}"
    );
}

#[test]
fn mlp_detect_window_matches_headless() {
    // A corner of the shipped test image, small enough for a software renderer.
    let full = image::open(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/mlp/text.png"))
        .unwrap()
        .to_luma8();
    let crop = image::imageops::crop_imm(&full, 96, 60, 96, 64).to_image();
    let path = scratch("text-crop.png");
    crop.save(&path).unwrap();
    let image = path.to_str().unwrap();
    window_matches_headless("mlp", &["mlp", "detect", image], 1);
    // The threshold lowered twice and the network's raw output shown.
    window_matches_headless(
        "mlp-output",
        &["mlp", "detect", image, "--keys=--", "--buffer", "1"],
        1,
    );
}

/// Each lecture-3 technique's window against its headless frame, on its second buffer where
/// it has one (Tab), so that a picture of a buffer and the frame are both checked.
fn lecture3_window_matches_headless(technique: &str, frames: usize, buffer: &str) {
    window_matches_headless(
        &format!("lecture3-{technique}"),
        &["lecture3", technique, "--buffer", buffer],
        frames,
    );
}

#[test]
fn lecture3_pyramid_window_matches_headless() {
    lecture3_window_matches_headless("pyramid", 1, "1");
}

#[test]
fn lecture3_displace_window_matches_headless() {
    lecture3_window_matches_headless("displace", 2, "1");
}

#[test]
fn lecture3_light_window_matches_headless() {
    lecture3_window_matches_headless("light", 1, "1");
}

#[test]
fn lecture3_function_window_matches_headless() {
    lecture3_window_matches_headless("function", 1, "1");
}

#[test]
fn lecture3_random_window_matches_headless() {
    lecture3_window_matches_headless("random", 3, "0");
}

#[test]
fn lecture3_depth_mask_window_matches_headless() {
    lecture3_window_matches_headless("depth-mask", 1, "0");
}

#[test]
fn lecture3_octree_window_matches_headless() {
    lecture3_window_matches_headless("octree", 1, "2");
}

#[test]
fn lecture3_histogram_window_matches_headless() {
    lecture3_window_matches_headless("histogram", 1, "0");
}

#[test]
fn the_probe_draws_the_same_readout_in_the_window_and_headless() {
    window_matches_headless(
        "collide-probe",
        &[
            "collide-scene",
            "touching-tori",
            "--triangles",
            "300",
            "--buffer",
            "2",
            "--probe",
            "128,100",
        ],
        2,
    );
}

/// `--glsl-dir` reaches the window's context: with the section 3.1 listing's first output
/// doubled in DIR, the window's frame (volume text included) must match the headless one made
/// with the same DIR, which differs from the frame made without it.
#[test]
fn the_window_reads_shaders_from_glsl_dir() {
    let dir = scratch("glsl-dir");
    let listing = "cg_ports/mass_integrands.frag";
    let source = classic_gpgpu::gl::shaders::find(listing).unwrap().source;
    assert!(source.contains("FragData[0] = c * p;"));
    let path = dir.join(listing);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(
        &path,
        source.replace("FragData[0] = c * p;", "FragData[0] = 2.0 * c * p;"),
    )
    .unwrap();
    let dir_arg = dir.to_str().unwrap();
    let demo = ["mass", "cube", "--resolution", "16"];
    let mut with_dir = demo.to_vec();
    with_dir.extend(["--glsl-dir", dir_arg]);
    window_matches_headless("mass-glsl-dir", &with_dir, 2);

    let headless = |extra: &[&str], name: &str| {
        let png = scratch(name);
        let mut args = demo.to_vec();
        args.extend(extra);
        args.extend([
            "--frames",
            "2",
            "--headless",
            "--screenshot",
            png.to_str().unwrap(),
        ]);
        let out = viewer(&args, None);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        image::open(&png).unwrap().to_rgba8()
    };
    let plain = headless(&[], "mass-plain.png");
    let doubled = headless(&["--glsl-dir", dir_arg], "mass-doubled.png");
    assert_ne!(plain, doubled, "the doubled volume shows in the frame");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn learn_ping_pong_window_matches_headless() {
    window_matches_headless("learn", &["learn", "ping-pong", "--buffer", "2"], 2);
}

/// Lecture 1: each technique's scene with its buffer insets, and its pair texture P0 (Tab),
/// in a window against the headless frame.
#[test]
fn lecture1_window_matches_headless() {
    for technique in ["self-collision", "pairwise"] {
        for buffer in ["0", "1"] {
            window_matches_headless(
                &format!("lecture1-{technique}-{buffer}"),
                &["lecture1", technique, "--buffer", buffer],
                2,
            );
        }
    }
    // Penetration depth has one buffer, the T cube faces, drawn over the scene's text.
    window_matches_headless("lecture1-penetration", &["lecture1", "penetration"], 2);
    // The walking figure in the room, two steps along its walk.
    window_matches_headless("lecture1-avatar-ccd", &["lecture1", "avatar-ccd"], 2);
}

/// A probe over no buffer (the text at the top of a lesson's frame) draws no label, in the
/// window as headless (the headless frame is checked against the frame without a probe in
/// tests/learn_feedback.rs).
#[test]
fn learn_probe_over_no_buffer_window_matches_headless() {
    window_matches_headless(
        "learn-probe-nowhere",
        &["learn", "reduction", "--probe", "200,4"],
        1,
    );
}

/// A lesson that iterates opens on its latest iterate (no `--buffer`), and `--buffer` takes a
/// buffer the first frame has not made in the old numbering (`--buffer 4`, the issue's), in
/// the window as headless.
#[test]
fn learn_ping_pong_opening_and_later_buffers_window_matches_headless() {
    window_matches_headless("learn-opening", &["learn", "ping-pong"], 3);
    window_matches_headless(
        "learn-buffer-4",
        &["learn", "ping-pong", "--buffer", "4"],
        1,
    );
}

/// The viewer with `args` on `display`, running until killed, and its stderr line by line.
fn spawn_viewer(args: &[&str], display: &str) -> (Child, std::sync::mpsc::Receiver<String>) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .arg("view")
        .args(args)
        .env_remove("WAYLAND_DISPLAY")
        .env("DISPLAY", display)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let stderr = child.stderr.take().expect("piped stderr");
    let (sender, receiver) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if sender.send(line).is_err() {
                return;
            }
        }
    });
    (child, receiver)
}

/// The first line holding `needle` within `limit` (the lines before it added to `seen`).
fn line_with(
    lines: &std::sync::mpsc::Receiver<String>,
    needle: &str,
    limit: Duration,
    seen: &mut Vec<String>,
) -> Option<String> {
    let start = Instant::now();
    while let Some(left) = limit.checked_sub(start.elapsed()) {
        match lines.recv_timeout(left) {
            Ok(line) if line.contains(needle) => return Some(line),
            Ok(line) => seen.push(line),
            Err(_) => return None,
        }
    }
    None
}

/// The shipped Jacobi step of lesson 2 with its weight 1/4 replaced by `weight`.
fn jacobi_weighted(weight: &str) -> String {
    let shipped = classic_gpgpu::gl::shaders::find("glsl/learn/jacobi.frag")
        .unwrap()
        .source;
    assert!(shipped.contains("o_value = 0.25 *"));
    shipped.replace("o_value = 0.25 *", &format!("o_value = {weight} *"))
}

/// Run `view learn ping-pong --glsl-dir DIR` in a window for `run_first`, then save the
/// Jacobi step `saves` times (wrong weights and right ones in turn), each `between` after
/// the last frame shown; the window's "reload shown" line for each save.
fn window_reloads(run_first: Duration, saves: usize, between: Duration) -> Vec<String> {
    let server = Xvfb::start();
    let dir = scratch("live-glsl");
    let path = dir.join("glsl/learn/jacobi.frag");
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(&path, jacobi_weighted("0.24")).unwrap();
    let dir_arg = dir.to_str().unwrap();
    let args = [
        "learn",
        "ping-pong",
        "--size",
        "256x192",
        "--glsl-dir",
        dir_arg,
    ];
    let (mut child, lines) = spawn_viewer(&args, &server.display);
    let mut seen = Vec::new();
    let opened = line_with(&lines, "via window", Duration::from_secs(120), &mut seen);
    let mut shown = Vec::new();
    if opened.is_some() {
        std::thread::sleep(run_first);
        for k in 0..saves {
            let weight = if k % 2 == 0 { "0.25" } else { "0.24" };
            std::fs::write(&path, jacobi_weighted(weight)).unwrap();
            match line_with(&lines, "reload shown:", Duration::from_secs(60), &mut seen) {
                Some(line) => shown.push(line),
                None => break,
            }
            std::thread::sleep(between);
        }
    }
    let _ = child.kill();
    let _ = child.wait();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(opened.is_some(), "the window did not open: {seen:?}");
    assert_eq!(shown.len(), saves, "a save was not shown: {seen:?}");
    shown
}

/// A shader saved while the window runs reaches the screen: the wrong Jacobi weights the
/// window opened with are replaced by the right ones, and the window logs the frame that
/// shows them with the time since the save (a figure for `--nocapture`, not asserted: the
/// quiet measurement is the ignored test below).
#[test]
fn a_shader_saved_while_the_window_runs_shows_in_it() {
    let shown = window_reloads(Duration::from_secs(1), 1, Duration::ZERO);
    println!("{}", shown[0]);
    assert!(
        shown[0].contains("glsl/learn/jacobi.frag saved")
            && shown[0].contains("the new shaders run"),
        "{}",
        shown[0]
    );
}

/// The reload latency as a learner meets it: the window runs 20 s (the issue's ~20 s wait came
/// after such a run), then the Jacobi step is saved five times, 2 s apart; each line gives the
/// time from the save to the frame that shows it. For a quiet machine:
/// `cargo test --release --test view -- --ignored --nocapture reload_latency`.
#[test]
#[ignore = "a measurement: 30 s of a window, run on a quiet machine"]
fn reload_latency_in_the_window() {
    for line in window_reloads(Duration::from_secs(20), 5, Duration::from_secs(2)) {
        println!("{line}");
    }
}
