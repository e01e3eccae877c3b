//! `classic-gpgpu lecture3 light --mode sss|environment`: the light hierarchy's other uses
//! (`src/lecture3/light_hierarchy/`), the GPU gathers beside the CPU reference, the tree search
//! against the brute-force sum; and what `--scene` and `--exposure` mean for every mode.

use classic_gpgpu::files;
use classic_gpgpu::gl::dump::{texture_png, DumpRange};
use classic_gpgpu::gl::Context;
use classic_gpgpu::lecture3::error::{check_range, Error};
use classic_gpgpu::lecture3::light_hierarchy::model::{load_model, model_alone, room_with};
use classic_gpgpu::lecture3::light_hierarchy::shade::Terms;
use classic_gpgpu::lecture3::light_hierarchy::uses::{base_exposure, default_scene, model_albedo};
use classic_gpgpu::lecture3::light_hierarchy::{LightUse, Scene};
use classic_gpgpu::report::lecture3::light_uses::use_run;
use serde_json::json;
use std::path::{Path, PathBuf};

/// What the light hierarchy is used for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LightMode {
    /// Indirect light from VPLs (the room, or --scene in place of its block).
    Indirect,
    /// Subsurface scattering: Jensen et al.'s dipole (skin) over irradiance samples.
    Sss,
    /// Environment light: a procedural sky as directional lights, visibility ignored.
    Environment,
}

impl LightMode {
    pub fn light_use(self) -> LightUse {
        match self {
            LightMode::Indirect => LightUse::Indirect,
            LightMode::Sss => LightUse::subsurface(),
            LightMode::Environment => LightUse::environment(),
        }
    }
}

/// `--exposure E`, in stops: finite, -20..=20.
pub fn check_exposure(stops: f32) -> Result<(), Error> {
    check_range("--exposure", stops as f64, -20.0, 20.0)
}

/// The picture's multiplier: the use's base times 2^stops.
pub fn exposure(light_use: &LightUse, stops: f32) -> f32 {
    base_exposure(light_use) * stops.exp2()
}

/// The scene of `light_use`: `model` (an OBJ file) placed for it, or its default.
pub fn scene(light_use: &LightUse, model: Option<&Path>) -> anyhow::Result<Scene> {
    let Some(path) = model else {
        return Ok(default_scene(light_use));
    };
    let triangles = load_model(path, model_albedo(light_use))?;
    Ok(match light_use {
        LightUse::Indirect => room_with(triangles),
        _ => model_alone(triangles),
    })
}

/// What `lecture3 light` needs for a mode other than indirect light.
pub struct UseArgs<'a> {
    pub mode: LightMode,
    pub model: Option<&'a Path>,
    pub lights: u32,
    pub size: u32,
    pub theta: f32,
    pub exposure: f32,
    pub npy: Option<PathBuf>,
    pub png: Option<&'a Path>,
}

/// Runs subsurface scattering or environment light: the brute force and the tree search on
/// the GPU and the CPU; prints what they found; writes the PNG and the npy.
/// Returns the JSON value, the text and the files written.
pub fn run_use(
    a: &UseArgs,
    ctx: &Context,
) -> anyhow::Result<(serde_json::Value, String, Vec<PathBuf>)> {
    let light_use = a.mode.light_use();
    let scene = scene(&light_use, a.model)?;
    let (run, lighting) = use_run(
        ctx,
        light_use,
        scene,
        a.lights,
        (a.size, a.size),
        &[a.theta],
        0.0,
    )?;
    let mut written = Vec::new();
    if let Some(path) = &a.npy {
        // `use_run` left the gather of `a.theta` in the target.
        let rgb: Vec<f32> = lighting
            .gathers
            .read()?
            .iter()
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        files::write_npy(path, &[a.size as usize, a.size as usize, 3], &rgb)?;
        written.push(path.clone());
    }
    if let Some(png) = a.png {
        lighting.shade(Terms::Indirect, exposure(&light_use, a.exposure))?;
        texture_png(lighting.shade.target.color(0), png, DumpRange::Auto)?;
        written.push(png.to_owned());
    }
    let row = &run.rows[0];
    let quantity = match light_use {
        LightUse::Subsurface(_) => "radiant exitance (dipole)",
        _ => "irradiance (sky, visibility ignored)",
    };
    let side = run.side;
    let text = format!(
        "{}: {} {} ({side}x{side}), {} receivers; theta {}: {:.1} summed and {:.1} nodes visited per \
         receiver; {quantity} relative RMS error {:.2e} against the brute force (CPU f64: \
         {:.2e}); GPU against CPU: brute force {:.1e}, tree {:.1e} of the largest value ({} \
         receivers with a decision within 1e-4 of its threshold left out)",
        run.mode,
        run.lights,
        light_use.lights_name(),
        run.receivers,
        row.theta,
        row.mean_gathered,
        row.mean_nodes,
        row.relative_rms_error,
        row.cpu_relative_rms_error,
        run.brute_gpu_vs_cpu,
        row.tree_gpu_vs_cpu,
        row.marginal,
    );
    Ok((json!({ "light_use": light_use, "run": run }), text, written))
}
