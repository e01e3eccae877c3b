//! Section 5: hydrostatic buoyancy of rigid bodies on still water. Each step the submerged
//! volume and centre of buoyancy of every body come from the n + 2 rendering passes of 5.2,
//! and the CPU integrates the rigid bodies under gravity, buoyancy and drag.

pub mod analytic;
pub mod batch;
pub mod forces;
pub mod render;
pub mod rigid_body;
pub mod scene;
pub mod simulation;
