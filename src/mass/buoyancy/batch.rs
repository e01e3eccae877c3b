//! Batching [section 5.2 for many bodies]: every body gets its own `R x R` tile (the
//! paper's 32 x 32) of one render target, posed and placed there by the CPU, so each of
//! the n + 2 passes is one pass for all bodies, an occlusion query per body says when it
//! is peeled through, and one reduction per target brings every tile to one texel: a
//! handful of passes and three small read-backs per step, whatever the number of bodies.

use super::forces::{Submerged, Water};
use super::simulation::{Body, Shape, SubmergedSolver};
use crate::gl::{profile, Context, GlError, Rect};
use crate::mass::framing::{covers_pixel_centre, Framing, PixelVertex};
use crate::mass::integrands::{Integrands, Placement, Soup};
use crate::mass::peel::{Job, PeelSettings, Peeler, PeelerOptions};
use glam::DVec3;

/// The GPU solver: the n + 2 passes for all bodies at once.
pub struct GpuSolver {
    peeler: Peeler,
    soup: Soup,
    resolution: u32,
    /// Tile side, the resolution rounded up to a power of two (reduction blocks).
    block: u32,
    columns: u32,
    capacity: usize,
    /// Peels of the last step (the deepest body's n).
    pub last_peels: usize,
    /// Steps whose peeling stopped at the limit with fragments left.
    pub truncated_steps: usize,
}

impl GpuSolver {
    /// Targets for up to `capacity` bodies of `shapes` at `resolution` x `resolution` each,
    /// evaluating eq. 4's four integrands, as pass 1 of section 5.2 does: the volume and
    /// the centre of buoyancy are all a step needs.
    pub fn new(
        ctx: &Context,
        shapes: &[Shape],
        capacity: usize,
        resolution: u32,
    ) -> Result<GpuSolver, GlError> {
        GpuSolver::with_integrands(ctx, shapes, capacity, resolution, Integrands::Eq4)
    }

    /// [`GpuSolver::new`] evaluating `integrands` (all ten, for pictures of every integrand
    /// of each peel).
    pub fn with_integrands(
        ctx: &Context,
        shapes: &[Shape],
        capacity: usize,
        resolution: u32,
        integrands: Integrands,
    ) -> Result<GpuSolver, GlError> {
        let block = resolution.next_power_of_two();
        let columns = (capacity.max(1) as f64).sqrt().ceil() as u32;
        let rows = (capacity.max(1) as u32).div_ceil(columns);
        let soup = Soup::new(ctx)?;
        let largest = |size: fn(&Shape) -> usize| shapes.iter().map(size).max().unwrap_or(0);
        soup.reserve(
            capacity,
            largest(|s| s.mesh.positions.len()),
            largest(|s| s.mesh.triangles.len()),
        )?;
        Ok(GpuSolver {
            peeler: Peeler::with_options(
                ctx,
                columns * block,
                rows * block,
                Some(block),
                PeelerOptions {
                    integrands,
                    ..PeelerOptions::default()
                },
            )?,
            soup,
            resolution,
            block,
            columns,
            capacity,
            last_peels: 0,
            truncated_steps: 0,
        })
    }

    /// The depth peeler (to capture its peels).
    pub fn peeler(&self) -> &super::super::peel::Peeler {
        &self.peeler
    }

    /// Peel with `settings` from now on (limit, order).
    pub fn set_settings(&mut self, settings: PeelSettings) -> Result<(), GlError> {
        self.peeler.set_settings(settings)
    }

    /// Size of the whole target (pixels).
    pub fn target_size(&self) -> (u32, u32) {
        let rows = (self.capacity.max(1) as u32).div_ceil(self.columns);
        (self.columns * self.block, rows * self.block)
    }

    /// The job of body `k`: framed by its world bounding box, in tile `k`, its posed
    /// vertices and the triangles that reach below the water added to the soup: the others
    /// could only make fragments the water test discards, and skipping them halves the
    /// vertex work of a floating body.
    fn job<'a>(
        &self,
        k: usize,
        name: &'a str,
        shape: &Shape,
        body: &Body,
        level: f64,
    ) -> Result<Job<'a>, GlError> {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let world = body.rigid.posed(&shape.mesh.positions);
        for &w in &world {
            lo = lo.min(w);
            hi = hi.max(w);
        }
        let framing = Framing::fit_box(lo, hi, self.resolution)
            .map_err(|e| GlError::Invalid(format!("buoyancy: {name}: {e}")))?;
        // A hair of slack keeps triangles touching the surface (fp32 depths).
        let keep_below = level + 1e-5 * (hi - lo).max_element().max(1.0);
        // Per vertex, once: below the water, and where it lies among the pixel centres.
        let below: Vec<bool> = world.iter().map(|w| w.z <= keep_below).collect();
        let pixels: Vec<PixelVertex> = world.iter().map(|&w| framing.pixel_vertex(w)).collect();
        let keep = |tri: &[u32; 3]| {
            let [a, b, c] = tri.map(|i| i as usize);
            (below[a] || below[b] || below[c])
                && covers_pixel_centre(&pixels[a], &pixels[b], &pixels[c])
        };
        let (col, row) = (k as u32 % self.columns, k as u32 / self.columns);
        let job = Job {
            body: name,
            group: k,
            framing,
            tile: Rect::new(
                col * self.block,
                row * self.block,
                self.resolution,
                self.resolution,
            ),
        };
        let place = Placement {
            framing,
            tile: job.tile,
            target: self.target_size(),
        };
        self.soup
            .push_body(&shape.mesh.triangles, &world, &place, keep);
        Ok(job)
    }
}

impl SubmergedSolver for GpuSolver {
    fn submerged(
        &mut self,
        shapes: &[Shape],
        bodies: &[Body],
        water: &Water,
    ) -> Result<Vec<Submerged>, String> {
        if bodies.len() > self.capacity {
            return Err(format!(
                "{} bodies for a solver made for {}",
                bodies.len(),
                self.capacity
            ));
        }
        let names: Vec<String> = bodies
            .iter()
            .enumerate()
            .map(|(k, b)| format!("body {k} ({})", shapes[b.shape].name))
            .collect();
        let run = || -> Result<_, GlError> {
            // One group per body: each has its own occlusion query, and a body peeled
            // through is not drawn again. (One draw for all bodies drew every body in
            // every layer: 1.7x the CPU time on llvmpipe; one per shape was no faster.)
            let setup = || -> Result<_, GlError> {
                self.soup.clear();
                let jobs = bodies
                    .iter()
                    .enumerate()
                    .map(|(k, b)| {
                        self.soup.begin_group();
                        self.job(k, &names[k], &shapes[b.shape], b, water.level)
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                self.soup.upload()?;
                Ok(jobs)
            };
            let jobs = {
                let _scope = profile::cpu_scope(
                    self.peeler.context(),
                    "buoyancy: pose, frame and index the bodies",
                );
                setup()?
            };
            self.peeler.run(&self.soup, &jobs, Some(water.level), None)
        };
        let batch = run().map_err(|e| e.to_string())?;
        self.last_peels = batch.peels;
        self.truncated_steps += batch.truncated as usize;
        Ok(batch.integrals.iter().map(Submerged::of).collect())
    }
}
