//! Paper 4: Kim, Kim, Ko & Terzopoulos, "Fast GPU computation of the mass properties of a
//! general shape and its application to buoyancy simulation", The Visual Computer 22(8),
//! 2006.
//!
//! The volume integrals of the mass properties become, by the divergence theorem with
//! `f = [0, 0, z]'` and friends, integrals of `sgn(n_z) z`, `sgn(n_z) xz`, ... over the
//! surface projected onto the xy plane [section 2.2, eq. 4 and 6]. The GPU evaluates those
//! integrands per fragment under an orthographic view, writing ten numbers to three render
//! targets at once [3.1], peels every depth layer of a non-convex body [3.2] and sums each
//! target by ping-pong reduction [3.3]. Section 5 restricts the same machinery to the part
//! of a body below a water surface (the n + 2 passes of 5.2) and drives rigid bodies with
//! the buoyant force.
//!
//! Notation follows the paper: `V`, `r = [r_x, r_y, r_z]'`, `n_z`, `I_xx` ... (eq. 6's
//! second moments), peels `T_1 .. T_n`, the water depth texture `T_dw`, the water patch
//! `T_w`. One file per step:
//!
//! | step | file |
//! |---|---|
//! | the ten integrals and their change of origin | [`integrals`] |
//! | framing: orthographic view of the body | [`framing`] |
//! | integrands (the section 3.1 listing) | [`integrands`] |
//! | depth peeling [3.2] | [`peel`] |
//! | depth peeling at the period's 24 bits | [`peel_depth`] |
//! | reduction and accumulation over peels [3.3] | [`reduce`] |
//! | volume, centre of mass, inertia [eq. 4-6] | [`assemble`] |
//! | Mirtich's analytic baseline | [`analytic`] |
//! | the part below a plane, for the analytic `--below` | [`clip`] |
//! | closed / open surface check | [`surface`] |
//! | closed forms for tests | [`closed_form`] |
//! | the whole method for one body | [`gpu`] |
//! | the GPU path's CPU reference | [`cpu_reference`] |
//! | then and now: one compute pass over the triangles (below a plane: clipped in the kernel) | [`compute`] |
//! | the paper's test objects [Table 1], OBJ files | [`models`] |
//! | buoyancy (section 5) | [`buoyancy`] |

pub mod analytic;
pub mod assemble;
pub mod buoyancy;
pub mod clip;
pub mod closed_form;
pub mod compute;
pub mod cpu_reference;
pub mod framing;
pub mod gpu;
pub mod integrals;
pub mod integrands;
pub mod models;
pub mod peel;
pub mod peel_depth;
pub mod peel_end;
pub mod pieces;
pub mod reduce;
pub mod surface;

pub use assemble::MassProperties;

/// A progress bar for long runs, hidden under `--json` or when stderr is not a terminal.
pub fn progress_bar(len: u64, hidden: bool, message: &'static str) -> indicatif::ProgressBar {
    if hidden {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{msg} {bar:40} {pos}/{len} [{elapsed}<{eta}]")
    {
        bar.set_style(style);
    }
    bar.set_message(message);
    bar
}
pub use integrals::VolumeIntegrals;
