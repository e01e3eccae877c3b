//! Technique 5: a generator per texel advanced by one ping-pong pass per frame, the numbers of
//! the last step probed against the CPU generators run as many steps.

use crate::gl::picture::{fixed, Panel, Scale};
use crate::gl::Context;
use crate::lecture3::random_texture::{HybridTaus, RandomTexture};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct RandomDemo {
    texture: RandomTexture,
    /// The CPU generators, one per texel, stepped with the GPU's.
    cpu: Vec<HybridTaus>,
    cpu_values: Vec<f32>,
    gpu_values: Vec<f32>,
    steps: usize,
}

const SIDE: u32 = 64;
const SEED: u64 = 2007;

impl RandomDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let texture = RandomTexture::new(ctx, SIDE, SIDE, SEED)?;
        let cpu = (0..(SIDE * SIDE) as u64)
            .map(|i| HybridTaus::seeded(SEED, i))
            .collect();
        Ok(RandomDemo {
            texture,
            cpu,
            cpu_values: Vec::new(),
            gpu_values: Vec::new(),
            steps: 0,
        })
    }
}

impl Demo for RandomDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        self.texture.step()?;
        self.gpu_values = self.texture.values()?;
        self.cpu_values = self.cpu.iter_mut().map(|g| g.next_f32()).collect();
        self.steps += 1;
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, _view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        if self.steps == 0 {
            return Ok(());
        }
        let shown = Shown {
            panel: Panel {
                title: format!("numbers of step {} ({SIDE}x{SIDE} generators)", self.steps),
                values: self.gpu_values.clone(),
                width: SIDE,
                height: SIDE,
                scale: Scale::fixed(0.0, 1.0),
            },
            probe_values: None,
            reference: Some(self.cpu_values.clone()),
        };
        inset::draw_picture(canvas, vec![shown], canvas.below_text())?;
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec!["random numbers".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let same = self.gpu_values == self.cpu_values;
        let mean = self.gpu_values.iter().map(|&v| v as f64).sum::<f64>()
            / self.gpu_values.len().max(1) as f64;
        vec![
            format!(
                "lecture 3, random texture: step {}, seed {SEED}",
                self.steps
            ),
            format!(
                "GPU numbers {} the CPU generators'; mean {}",
                if same {
                    "bit-exact with"
                } else {
                    "DIFFER from"
                },
                fixed(mean, 4)
            ),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }
}
