//! The full run's plan keeps every size and claim when its repeats are cut: a change that
//! times something fewer times must not drop a point of a sweep or the runs a claim is judged
//! on. No GL: the plan only.

use classic_gpgpu::report::lecture3::{theta_runs, THETAS};
use classic_gpgpu::timing::Runs;

/// Lecture 3's light sweep: every criterion of the sweep is still gathered, each criterion a
/// claim may pick (theta > 0) timed as the report's policy says, and only theta 0 (the tree
/// opening every cluster: the check against the brute force, never a claim's time) once.
#[test]
fn the_light_sweep_times_every_criterion_a_claim_can_take_by_the_policy() {
    assert_eq!(THETAS, [0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5]);
    for runs in [Runs::PAPER, Runs::exactly(3), Runs::exactly(7)] {
        for theta in THETAS {
            let got = theta_runs(theta, runs);
            if theta == 0.0 {
                assert_eq!(got, Runs::exactly(1));
            } else {
                assert_eq!(got, runs, "theta {theta}");
            }
        }
    }
}
