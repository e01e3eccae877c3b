//! Paper 4 live: a model turning while its mass properties are computed by depth peeling, each
//! peel's integrand buffers shown (Fig. 10), the GPU's volume and centre of mass beside
//! Mirtich's analytic ones [Kim et al., Sec. 3-4].

use super::peels::PeelChoice;
use crate::collide::snapshot::{self, Orbit, SnapshotModel};
use crate::gl::picture::fixed;
use crate::gl::Context;
use crate::mass::assemble::MassProperties;
use crate::mass::gpu::{GpuMass, GpuResult};
use crate::mass::peel::CapturedPeel;
use crate::mass::{analytic, models};
use crate::mesh::Mesh;
use crate::view::{Canvas, Demo, ViewState};
use glam::{Quat, Vec3};

pub struct MassDemo {
    name: String,
    rest: Mesh,
    turned: Mesh,
    gpu: GpuMass,
    resolution: u32,
    frame: usize,
    result: Option<(GpuResult, MassProperties, MassProperties)>,
    peels: Vec<CapturedPeel>,
    choice: PeelChoice,
}

impl MassDemo {
    pub fn new(ctx: &Context, model: &str, resolution: u32) -> anyhow::Result<Self> {
        if !(4..=512).contains(&resolution) {
            anyhow::bail!("--resolution {resolution}: must be between 4 and 512 in the viewer");
        }
        let rest = models::load(model).map_err(anyhow::Error::msg)?;
        let gpu = GpuMass::new(ctx, resolution)?;
        gpu.peeler().set_capture(true);
        Ok(MassDemo {
            name: model.to_string(),
            turned: rest.clone(),
            rest,
            gpu,
            resolution,
            frame: 0,
            result: None,
            peels: Vec::new(),
            choice: PeelChoice::default(),
        })
    }
}

impl Demo for MassDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        self.frame += 1;
        let t = self.frame as f32;
        let turn = Quat::from_rotation_z(0.07 * t) * Quat::from_rotation_x(0.05 * t);
        self.turned.positions = self.rest.positions.iter().map(|&p| turn * p).collect();
        let gpu = self.gpu.integrate(&self.turned, None, None)?;
        self.peels = self.gpu.peeler().take_captured();
        let got = MassProperties::from_integrals(&gpu.integrals, 1.0);
        let want = MassProperties::from_integrals(&analytic::volume_integrals(&self.turned), 1.0);
        self.result = Some((gpu, got, want));
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        if view.shown == 1 {
            return self.choice.draw_full(canvas, &self.peels);
        }
        canvas.clear([0.05, 0.05, 0.07, 1.0])?;
        let model = SnapshotModel {
            triangles: (0..self.turned.triangles.len())
                .map(|t| self.turned.triangle(t))
                .collect(),
            colliding: &[],
            cap_boxes: Vec::new(),
        };
        let nothing = SnapshotModel {
            triangles: Vec::new(),
            colliding: &[],
            cap_boxes: Vec::new(),
        };
        let orbit = Orbit {
            yaw: view.yaw,
            pitch: view.pitch,
            zoom: view.zoom * 0.8,
        };
        snapshot::draw(&model, &nothing, canvas.target(), orbit)?;
        self.choice.draw_strip(canvas, &self.peels)
    }

    fn buffers(&self) -> Vec<String> {
        vec!["model".into(), "peel layers".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "mass {}: {} triangles, {n}x{n} peels",
            self.name,
            self.turned.triangles.len(),
            n = self.resolution
        )];
        if let Some((gpu, got, want)) = &self.result {
            let c = |v: Vec3| {
                let f = |x: f32| fixed(x as f64, 3);
                format!("({}, {}, {})", f(v.x), f(v.y), f(v.z))
            };
            let error = (got.volume / want.volume - 1.0) * 100.0;
            let sign = if fixed(error, 2).starts_with('-') {
                ""
            } else {
                "+"
            };
            lines.push(format!(
                "peels {}  volume GPU {}  analytic {} ({sign}{}%)",
                gpu.peels,
                fixed(got.volume, 4),
                fixed(want.volume, 4),
                fixed(error, 2)
            ));
            lines.push(format!(
                "centre of mass GPU {}",
                c(got.center_of_mass.as_vec3())
            ));
            lines.push(format!(
                "centre of mass analytic {}",
                c(want.center_of_mass.as_vec3())
            ));
        }
        lines
    }

    fn timings(&self) -> String {
        self.result.as_ref().map_or(String::new(), |(gpu, ..)| {
            format!("peel+reduce {:.2} ms GPU", gpu.gpu_ms)
        })
    }

    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        PeelChoice::KEYS.to_vec()
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        Ok(self.choice.key(key, &self.peels))
    }
}
