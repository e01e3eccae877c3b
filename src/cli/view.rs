//! `view <demo>`: a paper's technique live in a window (`classic_gpgpu::view`), or with
//! `--headless` the same frames drawn off-screen into a PNG.

use anyhow::Context as _;
use classic_gpgpu::gl::Context;
use classic_gpgpu::report::paper1::TRIANGLE_BYTES;
use classic_gpgpu::values::{ranges, Count, Pair};
use classic_gpgpu::view::demos::lecture1::Technique as Lecture1Technique;
use classic_gpgpu::view::demos::lecture3::Technique as Lecture3Technique;
use classic_gpgpu::view::window::{self, WindowOptions};
use classic_gpgpu::view::{self as viewer, DemoSpec, ViewState};
use std::path::PathBuf;

use super::mass;

/// `--size` of the window or canvas.
const WINDOW: Pair = Pair {
    each: Count::new(
        "a side in pixels",
        16,
        8192,
        "a window's side; the overlay's text needs 16",
    ),
    separator: 'x',
    form: "WIDTHxHEIGHT (e.g. 960x600)",
    names: ("width", "height"),
};

/// `--probe X,Y`: a pixel of the window, from its top-left corner.
const PROBE: Pair = Pair {
    each: Count::new("a pixel", 0, 8191, "inside the largest window"),
    separator: ',',
    form: "X,Y (e.g. 120,80)",
    names: ("x", "y"),
};

/// `--frames`: 0 draws the first frame only.
const VIEW_FRAMES: Count = Count {
    least: 0,
    ..ranges::FRAMES
};

/// `--buffer`: the buffer's number among the demo's (0 the scene).
const BUFFER: Count = Count::new(
    "a buffer number",
    0,
    1023,
    "a demo shows tens of buffers; the demo says which it has",
);

#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    #[command(subcommand)]
    pub demo: DemoCommand,
    /// Window (or headless canvas) size in pixels, WIDTHxHEIGHT.
    #[arg(long, global = true, default_value = "960x600", value_parser = WINDOW)]
    pub size: (u32, u32),
    /// Run this many frames, then quit (with --screenshot: save the last one first).
    #[arg(long, global = true, value_parser = VIEW_FRAMES.of::<usize>())]
    pub frames: Option<usize>,
    /// Write the window's contents after --frames frames to this PNG.
    #[arg(long, global = true, requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Overwrite the --screenshot file if it exists.
    #[arg(long, global = true)]
    pub force: bool,
    /// No window: draw the same frame on the headless renderer (needs --screenshot).
    #[arg(long, global = true, requires = "screenshot")]
    pub headless: bool,
    /// The buffer shown first (Tab cycles in the window): any the demo makes, a later step's
    /// too. Without it, one that changes as the demo steps (the scene, a lesson's latest
    /// iterate).
    #[arg(long, global = true, value_parser = BUFFER.of::<usize>())]
    pub buffer: Option<usize>,
    /// Draw the help text over the frame.
    #[arg(long, global = true)]
    pub help_overlay: bool,
    /// The demo's own keys to press before the first frame, e.g. `mc` (crowd: vertex-shader
    /// skinning, LOD colours); `h` in the window lists them.
    #[arg(long, global = true, default_value = "", allow_hyphen_values = true)]
    pub keys: String,
    /// Start paused (space runs, right arrow steps).
    #[arg(long, global = true)]
    pub paused: bool,
    /// The texel probe at window pixel X,Y (from the top-left corner), as the mouse gives it:
    /// the buffer's texel there, its GPU value and its CPU reference's (printed too with
    /// --headless).
    #[arg(long, global = true, value_parser = PROBE)]
    pub probe: Option<(u32, u32)>,
}

#[derive(clap::Subcommand, Debug)]
pub enum DemoCommand {
    /// Paper 1: a deforming scene of Table III with its colliding triangles, CAP boxes and the
    /// buffers P0, P1..P3 and P1'.
    CollideScene {
        /// One of: interlocking-tori, touching-tori, merging-tori, bump-bunnies,
        /// happy-buddhas, intimate-animals.
        scene: Option<String>,
        /// Triangles per model instead of the paper's count.
        #[arg(long, value_parser = ranges::triangles(TRIANGLE_BYTES).of::<usize>())]
        triangles: Option<usize>,
    },
    /// Paper 4: a model turning, its volume and centre of mass by depth peeling beside the
    /// analytic ones, each peel's integrand targets (keys l and t cycle them).
    Mass {
        /// One of the paper's objects (cube, sphere, teapot, torus, knot, bunny, pipe) or an
        /// OBJ file.
        model: String,
        /// Peel resolution N (N x N).
        #[arg(long, default_value_t = 64, value_parser = mass::RESOLUTION.of::<u32>())]
        resolution: u32,
    },
    /// Paper 4, section 5: bodies floating on still water, the peel layers of the batch.
    Buoyancy {
        /// Number of bodies (the paper's scene has 50).
        #[arg(long, default_value_t = 50, value_parser = mass::BODIES.of::<usize>())]
        bodies: usize,
        /// Per-body peel resolution (the paper's 32).
        #[arg(long, default_value_t = 32, value_parser = mass::RESOLUTION.of::<u32>())]
        resolution: u32,
    },
    /// Paper 2: a crowd of soldiers walking, two-pass or vertex-shader skinning (key m), the
    /// pass-1 render target as an inset, LOD meshes coloured on demand (key c).
    Crowd {
        /// Number of characters.
        #[arg(long, default_value_t = 256, value_parser = super::crowd::CHARACTERS.of::<usize>())]
        characters: usize,
    },
    /// Paper 3: `mlp detect IMAGE`, the detected text pixels over the image, the threshold
    /// adjustable (keys + and -).
    #[command(subcommand)]
    Mlp(MlpDemo),
    /// The tutorial's lecture 1: self-collision of the swelling knotted tube, pairwise
    /// triangle tests in textures between two tori (the pair texture and its hierarchical
    /// levels one Tab away, each level's texel probed against the CPU encoding), or
    /// penetration depth (the six cube faces of the T buffer, probed against the CPU).
    Lecture1 {
        /// The technique, as `classic-gpgpu lecture1` names it.
        #[arg(value_enum)]
        technique: Lecture1Technique,
    },
    /// The tutorial's lecture 3: one technique live, its buffers one Tab away, each texel
    /// probed against the CPU reference.
    Lecture3 {
        /// The technique, as `classic-gpgpu lecture3` names it.
        #[arg(value_enum)]
        technique: Lecture3Technique,
    },
    /// A lesson of `learn` live: each pass's buffer (Tab), the checks against the CPU, one
    /// more iteration per step where the lesson iterates (ping-pong; it opens on the latest).
    Learn {
        /// The lesson's id or number (`classic-gpgpu learn --list`).
        id: String,
    },
}

#[derive(clap::Subcommand, Debug)]
pub enum MlpDemo {
    /// Text detection on an image (any format the `image` crate reads; e.g.
    /// assets/mlp/text.png).
    Detect {
        /// The image.
        image: PathBuf,
    },
}

/// The smallest canvas whose screenshot shows the demo: below it the overlay's text (8-pixel
/// glyphs, wrapped) covers the frame, and the PNG holds little but the caption. Measured by
/// drawing demos at falling sizes (lecture3 random, mass, lecture1 pairwise): at 256x192 each
/// still shows its picture below the text, at 160x120 the random demo shows text only.
pub const MIN_SCREENSHOT: (u32, u32) = (256, 192);

/// Refuses a screenshot of a canvas smaller than [`MIN_SCREENSHOT`], saying the minimum.
fn check_screenshot_size((w, h): (u32, u32)) -> anyhow::Result<()> {
    let (min_w, min_h) = MIN_SCREENSHOT;
    if w < min_w || h < min_h {
        anyhow::bail!(
            "--size {w}x{h}: a screenshot must be at least {min_w}x{min_h}; on a smaller canvas \
             the demo's text covers the picture and the PNG would hold little but the caption"
        );
    }
    Ok(())
}

impl DemoCommand {
    /// The files the demo reads, which a screenshot must never replace.
    fn inputs(&self) -> Vec<&std::path::Path> {
        match self {
            DemoCommand::Mass { model, .. } => vec![std::path::Path::new(model)],
            DemoCommand::Mlp(MlpDemo::Detect { image }) => vec![image.as_path()],
            _ => vec![],
        }
    }

    fn spec(&self) -> anyhow::Result<DemoSpec> {
        Ok(match self {
            DemoCommand::CollideScene { scene, triangles } => DemoSpec::CollideScene {
                scene: known_scene(scene.as_deref())?,
                triangles: *triangles,
            },
            DemoCommand::Mass { model, resolution } => DemoSpec::Mass {
                model: model.clone(),
                resolution: *resolution,
            },
            DemoCommand::Buoyancy { bodies, resolution } => DemoSpec::Buoyancy {
                bodies: *bodies,
                resolution: *resolution,
            },
            DemoCommand::Crowd { characters } => DemoSpec::Crowd {
                characters: *characters,
            },
            DemoCommand::Mlp(MlpDemo::Detect { image }) => DemoSpec::MlpDetect {
                image: image.clone(),
            },
            DemoCommand::Lecture1 { technique } => DemoSpec::Lecture1 {
                technique: *technique,
            },
            DemoCommand::Lecture3 { technique } => DemoSpec::Lecture3 {
                technique: *technique,
            },
            DemoCommand::Learn { id } => DemoSpec::Learn { id: id.clone() },
        })
    }
}

/// The scene `view collide-scene` was given, or an error that lists the scenes.
fn known_scene(scene: Option<&str>) -> anyhow::Result<String> {
    use classic_gpgpu::collide::scenes::SCENES;
    match scene {
        Some(name) if SCENES.contains(&name) => Ok(name.to_string()),
        Some(name) => anyhow::bail!(
            "view collide-scene: no scene '{name}'; the scenes are {}",
            SCENES.join(", ")
        ),
        None => anyhow::bail!(
            "view collide-scene needs a scene, one of {} (e.g. `classic-gpgpu view \
             collide-scene interlocking-tori`)",
            SCENES.join(", ")
        ),
    }
}

/// Run `view`; `context` makes the headless context when `--headless` asks for one, and the
/// window's context reads shaders from `glsl_dir` (`--glsl-dir`) and reloads them when saved.
pub fn run(
    args: &ViewArgs,
    glsl_dir: Option<PathBuf>,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<()> {
    let spec = args.demo.spec()?;
    if let Some(path) = &args.screenshot {
        classic_gpgpu::files::check_output(
            "--screenshot",
            path,
            &args.demo.inputs(),
            args.force,
            &["png"],
        )?;
    }
    let view = ViewState {
        help: args.help_overlay,
        probe: args.probe,
        ..ViewState::default()
    };
    if let Some((x, y)) = args.probe {
        if x >= args.size.0 || y >= args.size.1 {
            anyhow::bail!(
                "--probe {x},{y}: outside the {}x{} window",
                args.size.0,
                args.size.1
            );
        }
    }
    if args.headless {
        let ctx = context()?;
        let frames = args.frames.unwrap_or(0);
        let (pixels, probe) = viewer::headless_opening(
            &spec,
            &ctx,
            args.size,
            frames,
            &view,
            &args.keys,
            args.buffer,
        )
        .with_context(|| format!("view {}", spec.name()))?;
        for line in probe {
            println!("probe: {line}");
        }
        let path = args
            .screenshot
            .as_ref()
            .context("--headless needs --screenshot")?;
        // After the demo's own checks (its buffers, its keys), before anything is written.
        check_screenshot_size(args.size)?;
        viewer::write_png(&pixels, args.size, path)?;
        eprintln!(
            "wrote {} (frame {frames}, {})",
            path.display(),
            ctx.info().renderer_line()
        );
        return Ok(());
    }
    if args.screenshot.is_some() {
        check_screenshot_size(args.size)?;
    }
    window::run(
        &spec,
        WindowOptions {
            size: args.size,
            frames: args.frames,
            screenshot: args.screenshot.clone(),
            paused: args.paused,
            view,
            buffer: args.buffer,
            keys: args.keys.clone(),
            glsl_dir,
        },
    )
    .with_context(|| format!("view {}", spec.name()))
}
