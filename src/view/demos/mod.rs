//! The demos, one file per paper, and [`DemoSpec`]: which demo, with its arguments, as the
//! command line names it.

mod collide;

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
}

impl DemoSpec {
    /// The demo as typed after `view` (`collide-scene touching-tori`).
    pub fn name(&self) -> String {
        match self {
            DemoSpec::CollideScene { scene, .. } => format!("collide-scene {scene}"),
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
        }
    }

    /// The headless commands that do the same work, for error messages.
    pub fn headless_hint(&self) -> String {
        let paper = match self {
            DemoSpec::CollideScene { scene, triangles } => format!(
                "classic-gpgpu collide-scene {scene}{}",
                triangles.map_or(String::new(), |t| format!(" --triangles {t}"))
            ),
        };
        format!(
            "`classic-gpgpu view {} --headless --screenshot frame.png` (or `{paper}`)",
            self.arguments()
        )
    }

    /// Build the demo on `ctx` for a canvas of `size` pixels.
    pub fn build(&self, ctx: &Context, size: (u32, u32)) -> anyhow::Result<Box<dyn Demo>> {
        let _ = size;
        Ok(match self {
            DemoSpec::CollideScene { scene, triangles } => {
                Box::new(collide::CollideDemo::new(ctx, scene, *triangles)?)
            }
        })
    }
}
