//! Lecture 1, penetration depth by rasterized Minkowski sums live (`view lecture1
//! penetration`): a small cube circling inside the corner of an L of two boxes; each step runs
//! the closest-point query and shows the T buffer's six cube faces on one scale, each texel
//! probed against the CPU's per-ray exit, with the depth, its direction and the rasterized
//! bound in the overlay.

use crate::gl::Context;
use crate::lecture1::penetration::minkowski::minkowski_sums;
use crate::lecture1::penetration::pieces::{pieces_of_meshes, Piece};
use crate::lecture1::penetration::reference::{rounded_to_f32, t_buffer};
use crate::lecture1::penetration::scenes::corner_pair;
use crate::lecture1::penetration::{
    exit_panels, scaled, Formulation, Options, Penetration, PenetrationQuery,
};
use crate::mesh::cuboid;
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};
use glam::Vec3;

/// Texels per cube face.
const RESOLUTION: usize = 32;
/// Radians of the cube's circle per step.
const STEP: f32 = 0.25;

pub struct PenetrationDemo {
    query: PenetrationQuery,
    a: Vec<Piece>,
    frame: usize,
    result: Penetration,
    /// The CPU's T buffer of the same frame (model units).
    reference: Vec<f32>,
}

impl PenetrationDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<PenetrationDemo> {
        let query = PenetrationQuery::new(ctx)?;
        let a = corner_pair().a;
        let (result, reference) = Self::run(&query, &a, 0)?;
        Ok(PenetrationDemo {
            query,
            a,
            frame: 0,
            result,
            reference,
        })
    }

    /// B at frame `frame`: a cube of half side 0.05 on a circle inside the L's corner square.
    fn b_at(frame: usize) -> anyhow::Result<Vec<Piece>> {
        let angle = frame as f32 * STEP;
        let centre = Vec3::new(0.5 + 0.4 * angle.cos(), 0.5 + 0.4 * angle.sin(), 0.0);
        pieces_of_meshes("B", &[cuboid(Vec3::splat(0.05)).translated(centre)])
    }

    fn run(
        query: &PenetrationQuery,
        a: &[Piece],
        frame: usize,
    ) -> anyhow::Result<(Penetration, Vec<f32>)> {
        let b = Self::b_at(frame)?;
        let result = query.run(
            a,
            &b,
            &Options {
                resolution: RESOLUTION,
                formulation: Formulation::Classic,
                keep_exits: true,
            },
        )?;
        let unit: Vec<_> = minkowski_sums(a, &b)?
            .iter()
            .map(|s| scaled(s, 1.0 / result.scale))
            .collect();
        let reference = t_buffer(&rounded_to_f32(&unit), RESOLUTION)
            .iter()
            .map(|t| (*t as f64 * result.scale) as f32)
            .collect();
        Ok((result, reference))
    }
}

impl Demo for PenetrationDemo {
    /// The cube moves one step along its circle; the query runs again.
    fn step(&mut self) -> anyhow::Result<()> {
        self.frame += 1;
        (self.result, self.reference) = Self::run(&self.query, &self.a, self.frame)?;
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, _view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        let Some(exits) = &self.result.exits else {
            return Ok(());
        };
        let reference = exit_panels(&self.reference, RESOLUTION);
        let shown: Vec<Shown> = exit_panels(exits, RESOLUTION)
            .into_iter()
            .zip(reference)
            .map(|(panel, cpu)| Shown {
                probe_values: None,
                reference: Some(cpu.values),
                panel,
            })
            .collect();
        inset::draw_picture(canvas, shown, canvas.below_text())?;
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec!["T: where each ray leaves the union of the Minkowski sums".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let r = &self.result;
        let mut lines = vec![format!(
            "lecture 1, penetration depth: frame {}, {} sums, {} passes, {RESOLUTION} texels \
             per cube face",
            self.frame, r.sums_kept, r.passes
        )];
        match r.direction {
            Some(d) => lines.push(format!(
                "depth {:.5} along ({:.3}, {:.3}, {:.3}); rasterized bound {:.5}",
                r.depth, d[0], d[1], d[2], r.upper_bound
            )),
            None => lines.push("no overlap: depth 0".into()),
        }
        lines
    }

    fn timings(&self) -> String {
        format!("penetration depth: passes {:.2} ms GPU", self.result.gpu_ms)
    }
}
