//! Section 5: hydrostatic buoyancy of rigid bodies on still water. Each step the submerged
//! volume and centre of buoyancy of every body come from the n + 2 rendering passes of 5.2,
//! and the CPU integrates the rigid bodies under gravity, buoyancy and drag.
//!
//! | step | file |
//! |---|---|
//! | n + 2 passes for all bodies, as tiles of one target; eq. 4's four integrands in one render target | [`batch`] (on [`crate::mass::peel`]) |
//! | the CPU reference: clip + Mirtich | [`analytic`] |
//! | the compute formulation: clip in the kernel, one dispatch | [`compute`] |
//! | gravity, buoyancy [eq. 7], drag (optional damping) | [`forces`] |
//! | rigid-body state and integrator | [`rigid_body`] |
//! | the simulation loop | [`simulation`] |
//! | the scene of 5.3 / Fig. 9 | [`scene`] |
//! | frames as PNG (Fig. 9, 10) | [`render`] |
//! | the GPU solver against the CPU one, interleaved | [`race`] |

pub mod analytic;
pub mod batch;
pub mod compute;
pub mod forces;
pub mod race;
pub mod render;
pub mod rigid_body;
pub mod scene;
pub mod simulation;
