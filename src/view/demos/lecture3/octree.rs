//! Octrees on the GPU: rays cast through the occupancy octree of a point set, the camera
//! orbiting the cube; the distance to each pixel's first voxel against the CPU's, the steps of
//! the octree cast and of the flat walk, and every level of the octree (z slices tiled) against
//! the CPU's.

use super::{against, cleared, gpu_beside_cpu, square};
use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::lecture3::displacement::Camera;
use crate::lecture3::octree::cast::{centre, CastTarget};
use crate::lecture3::octree::grid::{self, shape_points, VoxelGrid};
use crate::lecture3::octree::levels::{cpu_levels, Level};
use crate::lecture3::octree::reference::CastReference;
use crate::lecture3::octree::{OctreeCaster, Search};
use crate::view::inset;
use crate::view::{Canvas, Demo, ViewState};

pub struct OctreeDemo {
    caster: OctreeCaster,
    target: CastTarget,
    cpu: Vec<Level>,
    gpu: Vec<Level>,
    frame: usize,
    /// Distance to the first voxel (0: none), GPU octree cast and CPU.
    distance: Vec<f32>,
    cpu_distance: Vec<f32>,
    octree_steps: Vec<f32>,
    flat_steps: Vec<f32>,
}

/// Image side (pixels) and leaf grid side.
const SIDE: u32 = 96;
const RESOLUTION: u32 = 32;
/// Degrees the camera turns per frame.
const TURN: f32 = 6.0;

impl OctreeDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let voxels = VoxelGrid::from_points(RESOLUTION, &shape_points(20_000, 1))?;
        let caster = OctreeCaster::new(ctx, &voxels)?;
        let target = caster.target(SIDE, SIDE)?;
        Ok(OctreeDemo {
            gpu: caster.levels.read()?,
            cpu: cpu_levels(&voxels),
            caster,
            target,
            frame: 0,
            distance: Vec::new(),
            cpu_distance: Vec::new(),
            octree_steps: Vec::new(),
            flat_steps: Vec::new(),
        })
    }

    fn camera(&self) -> Camera {
        let azimuth = 30.0 + TURN * self.frame as f32;
        Camera::orbit(centre(), 3.5, azimuth, 25.0, SIDE, SIDE)
    }
}

impl Demo for OctreeDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        self.frame += 1;
        let camera = self.camera();
        self.caster.cast(&self.target, &camera, Search::Flat)?;
        let flat = self.caster.read(&self.target)?;
        flat.check_finished()?;
        self.flat_steps = flat.steps();
        self.caster.cast(&self.target, &camera, Search::Octree)?;
        let octree = self.caster.read(&self.target)?;
        octree.check_finished()?;
        self.distance = octree.distances();
        self.octree_steps = octree.steps();
        self.cpu_distance = CastReference::trace(&self.cpu, &camera)
            .hits()
            .iter()
            .map(|h| h.map_or(0.0, |h| h.t as f32))
            .collect();
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        if !cleared(canvas, self.frame)? {
            return Ok(());
        }
        let area = canvas.below_text();
        let shown = match view.shown % 3 {
            0 => gpu_beside_cpu(
                SIDE,
                (
                    "GPU octree cast: distance to the first voxel",
                    &self.distance,
                ),
                ("CPU flat walk's distance", &self.cpu_distance),
            ),
            1 => {
                let scale = Scale::of([self.octree_steps.as_slice(), self.flat_steps.as_slice()]);
                vec![
                    square("octree steps per pixel", &self.octree_steps, SIDE, scale).into(),
                    square("flat walk steps per pixel", &self.flat_steps, SIDE, scale).into(),
                ]
            }
            _ => self
                .gpu
                .iter()
                .zip(&self.cpu)
                .enumerate()
                .map(|(k, (g, c))| {
                    let (w, h) = grid::texture_size(g.n);
                    let level = Panel {
                        title: format!("level {k} ({0}^3, z slices tiled)", g.n),
                        values: g.tiled(),
                        width: w,
                        height: h,
                        scale: Scale::fixed(0.0, 1.0),
                    };
                    against(level, &c.tiled())
                })
                .collect(),
        };
        inset::draw_picture(canvas, shown, area)?;
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec![
            "distance to the first voxel".into(),
            "steps: octree and flat".into(),
            "octree levels".into(),
        ]
    }

    fn overlay(&self) -> Vec<String> {
        let mean = |v: &[f32]| v.iter().map(|&s| s as f64).sum::<f64>() / v.len().max(1) as f64;
        let differ = self
            .distance
            .iter()
            .zip(&self.cpu_distance)
            .filter(|(g, c)| (**g > 0.0) != (**c > 0.0))
            .count();
        vec![
            format!(
                "lecture 3, octree on the GPU: {RESOLUTION}^3 voxels of 20000 points, {} levels, \
                 {SIDE}x{SIDE} rays",
                self.cpu.len()
            ),
            format!(
                "steps per pixel: octree {:.1}, flat {:.1}; hit or miss unlike the CPU: {differ}",
                mean(&self.octree_steps),
                mean(&self.flat_steps)
            ),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }
}
