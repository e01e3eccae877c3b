//! The behaviour layer: characters walk on the ground plane towards wandering goals, with
//! steering (seek + separation, after Reynolds) that keeps them apart. The animation
//! phase advances by the distance walked divided by the clip's stride, so every
//! character has its own animation time and speed and the feet keep pace with the body.

use std::collections::HashMap;

use glam::{DAffine3, DQuat, DVec3, Vec2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// One character on the plane (x, z), facing `heading` (radians about +y, 0 = +z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Agent {
    pub position: Vec2,
    pub velocity: Vec2,
    pub heading: f32,
    /// Animation phase in cycles (any real number; the clip loops).
    pub phase: f64,
    /// Preferred walking speed (m/s).
    pub pace: f32,
    pub goal: Vec2,
}

impl Agent {
    /// Model-to-world transform: rotate by the heading, then stand at the position.
    pub fn model_matrix(&self) -> DAffine3 {
        DAffine3::from_rotation_translation(
            DQuat::from_rotation_y(self.heading as f64),
            DVec3::new(self.position.x as f64, 0.0, self.position.y as f64),
        )
    }
}

/// Tunables of the steering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteeringParams {
    /// Characters closer than this push each other apart (m).
    pub separation_radius: f32,
    /// Strength of the push relative to goal seeking.
    pub separation_weight: f32,
    /// How quickly velocity follows the steering (1/s).
    pub agility: f32,
    /// The walkable rectangle: min and max corners (x, z).
    pub bounds: (Vec2, Vec2),
}

/// A crowd of agents with its own random stream (deterministic for a seed: equal crowds
/// stay equal step by step).
#[derive(Clone, Debug, PartialEq)]
pub struct Crowd {
    pub agents: Vec<Agent>,
    pub params: SteeringParams,
    rng: ChaCha8Rng,
}

impl Crowd {
    /// `n` agents on a jittered square grid of pitch `spacing` centred at the origin, with
    /// random headings, phases and paces around `pace`.
    pub fn new(n: usize, spacing: f32, pace: f32, seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let side = (n as f32).sqrt().ceil().max(1.0);
        let half = 0.5 * side * spacing;
        let bounds = (Vec2::splat(-half), Vec2::splat(half));
        let agents = (0..n)
            .map(|i| {
                let cell = Vec2::new((i % side as usize) as f32, (i / side as usize) as f32);
                let jitter = Vec2::new(rng.gen_range(-0.25..0.25), rng.gen_range(-0.25..0.25));
                let position = (cell + Vec2::splat(0.5) + jitter) * spacing - Vec2::splat(half);
                Agent {
                    position,
                    velocity: Vec2::ZERO,
                    heading: rng.gen_range(-std::f32::consts::PI..std::f32::consts::PI),
                    phase: rng.gen_range(0.0..1.0),
                    pace: pace * rng.gen_range(0.8..1.2),
                    goal: random_point(&mut rng, bounds),
                }
            })
            .collect();
        let params = SteeringParams {
            separation_radius: 0.8 * spacing,
            separation_weight: 2.0,
            agility: 2.0,
            bounds,
        };
        Self {
            agents,
            params,
            rng,
        }
    }

    /// Advances the crowd by `dt` seconds; `stride` is the clip's metres per cycle.
    pub fn step(&mut self, dt: f32, stride: f64) {
        let grid = NeighbourGrid::new(&self.agents, self.params.separation_radius);
        let pushes: Vec<Vec2> = (0..self.agents.len())
            .map(|i| grid.separation(&self.agents, i, self.params.separation_radius))
            .collect();
        let (lo, hi) = self.params.bounds;
        for (agent, push) in self.agents.iter_mut().zip(pushes) {
            if agent.position.distance(agent.goal) < 1.0 {
                agent.goal = random_point(&mut self.rng, self.params.bounds);
            }
            let desired = (agent.goal - agent.position).normalize_or_zero() * agent.pace;
            let steer =
                (desired - agent.velocity) + push * self.params.separation_weight * agent.pace;
            agent.velocity += steer * (self.params.agility * dt).min(1.0);
            agent.velocity = agent.velocity.clamp_length_max(1.5 * agent.pace);
            agent.position = (agent.position + agent.velocity * dt).clamp(lo, hi);
            let speed = agent.velocity.length();
            if speed > 1e-3 {
                agent.heading = agent.velocity.x.atan2(agent.velocity.y);
            }
            agent.phase += (speed * dt) as f64 / stride;
        }
    }

    /// Smallest distance between two agents (for tests and the CLI's report).
    pub fn min_separation(&self) -> f32 {
        let mut best = f32::INFINITY;
        for (i, a) in self.agents.iter().enumerate() {
            for b in &self.agents[i + 1..] {
                best = best.min(a.position.distance(b.position));
            }
        }
        best
    }
}

fn random_point(rng: &mut ChaCha8Rng, (lo, hi): (Vec2, Vec2)) -> Vec2 {
    Vec2::new(rng.gen_range(lo.x..=hi.x), rng.gen_range(lo.y..=hi.y))
}

/// Largest push of one neighbour (keeps coincident agents from exploding apart).
const MAX_PUSH: f32 = 4.0;

/// Agents bucketed in square cells of the separation radius, so a neighbour query looks
/// at 3x3 cells instead of the whole crowd.
struct NeighbourGrid {
    cell: f32,
    cells: HashMap<(i32, i32), Vec<usize>>,
}

impl NeighbourGrid {
    fn new(agents: &[Agent], cell: f32) -> Self {
        let mut cells: HashMap<(i32, i32), Vec<usize>> = HashMap::new();
        for (i, a) in agents.iter().enumerate() {
            cells
                .entry(Self::key(a.position, cell))
                .or_default()
                .push(i);
        }
        Self { cell, cells }
    }

    fn key(p: Vec2, cell: f32) -> (i32, i32) {
        ((p.x / cell).floor() as i32, (p.y / cell).floor() as i32)
    }

    /// Sum of pushes away from every neighbour within `radius`, each `radius / d - 1`: zero
    /// at the radius and growing steeply on approach, so a seek towards a goal behind a
    /// neighbour cannot push through it.
    fn separation(&self, agents: &[Agent], i: usize, radius: f32) -> Vec2 {
        let p = agents[i].position;
        let (cx, cz) = Self::key(p, self.cell);
        let mut push = Vec2::ZERO;
        for dx in -1..=1 {
            for dz in -1..=1 {
                let Some(bucket) = self.cells.get(&(cx + dx, cz + dz)) else {
                    continue;
                };
                for &j in bucket {
                    let away = p - agents[j].position;
                    let d = away.length();
                    if j != i && d < radius {
                        let direction = if d > 1e-6 {
                            away / d
                        } else {
                            // Coincident agents: separate them along a fixed, index-based axis.
                            Vec2::from_angle(i as f32)
                        };
                        push += direction * (radius / d.max(1e-3) - 1.0).min(MAX_PUSH);
                    }
                }
            }
        }
        push
    }
}
