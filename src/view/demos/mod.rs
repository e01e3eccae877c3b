//! The demos, one file per paper, and [`DemoSpec`]: which demo, with its arguments, as the
//! command line names it.

mod buoyancy;
mod collide;
mod crowd;
mod learn;
pub mod lecture1;
pub mod lecture3;
mod mass;
mod mlp;
mod peels;

use super::Demo;
use crate::gl::Context;

/// A demo and its arguments.
#[derive(Clone, Debug, PartialEq)]
pub enum DemoSpec {
    /// Paper 1: a deforming scene of Table III (`triangles` per model instead of the paper's).
    CollideScene {
        scene: String,
        triangles: Option<usize>,
    },
    /// Paper 4: a model (paper object or OBJ) turning, peeled at `resolution`.
    Mass { model: String, resolution: u32 },
    /// Paper 4, section 5: `bodies` floating, each peeled at `resolution`.
    Buoyancy { bodies: usize, resolution: u32 },
    /// Paper 2: `characters` soldiers walking, LODs by distance.
    Crowd { characters: usize },
    /// Paper 3: text detection on an image.
    MlpDetect { image: std::path::PathBuf },
    /// The tutorial's lecture 1: one technique.
    Lecture1 { technique: lecture1::Technique },
    /// The tutorial's lecture 3: one technique.
    Lecture3 { technique: lecture3::Technique },
    /// A lesson of `learn`: its passes' buffers, its checks.
    Learn { id: String },
}

impl DemoSpec {
    /// The demo as typed after `view` (`collide-scene touching-tori`).
    pub fn name(&self) -> String {
        match self {
            DemoSpec::CollideScene { scene, .. } => format!("collide-scene {scene}"),
            DemoSpec::Mass { model, .. } => format!("mass {model}"),
            DemoSpec::Buoyancy { .. } => "buoyancy".to_string(),
            DemoSpec::Crowd { .. } => "crowd".to_string(),
            DemoSpec::MlpDetect { image } => format!("mlp detect {}", image.display()),
            DemoSpec::Lecture1 { technique } => format!("lecture1 {}", technique.name()),
            DemoSpec::Lecture3 { technique } => format!("lecture3 {}", technique.name()),
            DemoSpec::Learn { id } => format!("learn {id}"),
        }
    }

    /// The demo's arguments as typed after `view` (options included).
    fn arguments(&self) -> String {
        match self {
            DemoSpec::CollideScene { scene, triangles } => {
                let mut s = format!("collide-scene {scene}");
                if let Some(t) = triangles {
                    s.push_str(&format!(" --triangles {t}"));
                }
                s
            }
            DemoSpec::Mass { model, resolution } => {
                format!("mass {model} --resolution {resolution}")
            }
            DemoSpec::Buoyancy { bodies, resolution } => {
                format!("buoyancy --bodies {bodies} --resolution {resolution}")
            }
            DemoSpec::Crowd { characters } => format!("crowd --characters {characters}"),
            DemoSpec::MlpDetect { image } => format!("mlp detect {}", image.display()),
            DemoSpec::Lecture1 { technique } => format!("lecture1 {}", technique.name()),
            DemoSpec::Lecture3 { technique } => format!("lecture3 {}", technique.name()),
            DemoSpec::Learn { id } => format!("learn {id}"),
        }
    }

    /// The headless commands that do the same work, for error messages.
    pub fn headless_hint(&self) -> String {
        let paper = match self {
            DemoSpec::CollideScene { scene, triangles } => format!(
                "classic-gpgpu collide-scene {scene}{}",
                triangles.map_or(String::new(), |t| format!(" --triangles {t}"))
            ),
            DemoSpec::Mass { model, resolution } => {
                format!("classic-gpgpu mass {model} --resolution {resolution} --dump DIR")
            }
            DemoSpec::Buoyancy { bodies, resolution } => format!(
                "classic-gpgpu buoyancy --bodies {bodies} --resolution {resolution} \
                 --png-every 10 DIR"
            ),
            DemoSpec::Crowd { characters } => {
                format!("classic-gpgpu crowd --characters {characters} --lod --png crowd.png")
            }
            DemoSpec::MlpDetect { image } => {
                format!(
                    "classic-gpgpu mlp detect {} --out mask.png",
                    image.display()
                )
            }
            DemoSpec::Lecture1 { technique } => match technique {
                lecture1::Technique::SelfCollision => {
                    "classic-gpgpu lecture1 self-collision --scene knotted-tube --frames 8 --dt 0.25"
                        .to_string()
                }
                lecture1::Technique::Pairwise => "classic-gpgpu mesh generate torus --out \
                    torus.obj && classic-gpgpu lecture1 pairwise torus.obj torus.obj"
                    .into(),
                lecture1::Technique::Penetration => "classic-gpgpu mesh generate cube --out \
                    cube.obj && classic-gpgpu lecture1 penetration cube.obj cube.obj --png \
                    t.png"
                    .into(),
                lecture1::Technique::AvatarCcd => "classic-gpgpu lecture1 avatar-ccd --json".into(),
            },
            DemoSpec::Lecture3 { technique } => {
                format!("classic-gpgpu lecture3 {}", technique.name())
            }
            DemoSpec::Learn { id } => format!("classic-gpgpu learn {id} --png DIR"),
        };
        format!(
            "`classic-gpgpu view --headless --frames 1 --screenshot frame.png {}` (or `{paper}`)",
            self.arguments()
        )
    }

    /// Build the demo on `ctx` for a canvas of `size` pixels.
    pub fn build(&self, ctx: &Context, size: (u32, u32)) -> anyhow::Result<Box<dyn Demo>> {
        Ok(match self {
            DemoSpec::CollideScene { scene, triangles } => {
                Box::new(collide::CollideDemo::new(ctx, scene, *triangles)?)
            }
            DemoSpec::Mass { model, resolution } => {
                Box::new(mass::MassDemo::new(ctx, model, *resolution)?)
            }
            DemoSpec::Buoyancy { bodies, resolution } => {
                Box::new(buoyancy::BuoyancyDemo::new(ctx, *bodies, *resolution)?)
            }
            DemoSpec::Crowd { characters } => {
                Box::new(crowd::CrowdDemo::new(ctx, *characters, size)?)
            }
            DemoSpec::MlpDetect { image } => Box::new(mlp::MlpDemo::new(ctx, image)?),
            DemoSpec::Lecture1 { technique } => technique.build(ctx)?,
            DemoSpec::Lecture3 { technique } => technique.build(ctx)?,
            DemoSpec::Learn { id } => Box::new(learn::LearnDemo::new(ctx, id)?),
        })
    }
}
