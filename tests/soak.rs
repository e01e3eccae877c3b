//! Soak tests: long runs whose memory must stay flat, so that a leak (a GL object not freed,
//! a buffer that grows per frame) shows up. Ignored by default (about a minute each on
//! llvmpipe); run them with
//!
//! ```sh
//! cargo test --release --test soak -- --ignored
//! ```
//!
//! Measured on llvmpipe (2 cores): 2,000 collide frames flat at about 105 MB and 1,500
//! buoyancy steps of the paper's 50 bodies flat at about 119 MB (as `collide-scene` and
//! `buoyancy` processes); in this test process, run one after the other: buoyancy 112.0 MB
//! after the warm-up and after 1,500 steps, collide 131.2 MB after 200 and after 2,000 frames
//! (llvmpipe, 2 cores). Each test takes the process's resident set after a warm-up (a tenth
//! of the run: shader compilation, the driver's pools) and fails if it then grows by more
//! than [`LEAK_MB`].

use classic_gpgpu::collide::pipeline::{Options, StreamingCollider};
use classic_gpgpu::collide::scenes::Scene;
use classic_gpgpu::mass::buoyancy::batch::GpuSolver;
use classic_gpgpu::mass::buoyancy::scene;
use common::context;
use std::sync::Mutex;

mod common;

/// Growth after the warm-up that counts as a leak: 1,800 frames leaking 10 KB each.
const LEAK_MB: f64 = 16.0;

/// The two tests measure one process's memory: never at the same time.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// This process's resident set (VmRSS), MB.
fn rss_mb() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status");
    let kb: f64 = status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse().ok())
        .expect("VmRSS in /proc/self/status");
    kb / 1024.0
}

/// Runs `steps` steps of `step`, and checks the resident set after the warm-up against the
/// largest one seen after it.
fn assert_flat(what: &str, steps: usize, mut step: impl FnMut(usize)) {
    let warm_up = steps / 10;
    let mut after_warm_up = 0.0;
    let mut largest: f64 = 0.0;
    for i in 0..steps {
        step(i);
        if i + 1 == warm_up {
            after_warm_up = rss_mb();
        }
        if i >= warm_up && i % 50 == 0 {
            largest = largest.max(rss_mb());
        }
    }
    let end = rss_mb();
    largest = largest.max(end);
    eprintln!(
        "{what}: {after_warm_up:.1} MB after {warm_up} steps, at most {largest:.1} MB, {end:.1} MB after {steps}"
    );
    assert!(
        largest - after_warm_up <= LEAK_MB,
        "{what}: memory grew from {after_warm_up:.1} MB to {largest:.1} MB after the warm-up (more than {LEAK_MB} MB): a leak"
    );
}

#[test]
#[ignore = "soak: about a minute; cargo test --release --test soak -- --ignored"]
fn two_thousand_collide_frames_keep_memory_flat() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let ctx = context();
    let scene = Scene::build("interlocking-tori", None).unwrap();
    let mut collider =
        StreamingCollider::new(&ctx, &scene.x.rest, &scene.y.rest, Options::default()).unwrap();
    let mut pairs = 0;
    assert_flat("collide, interlocking tori", 2000, |f| {
        let (px, py) = scene.frame(f);
        pairs += collider.frame(&px, &py).unwrap().pairs.len();
    });
    assert!(
        pairs > 0,
        "the tori never touched: the run exercised too little"
    );
}

#[test]
#[ignore = "soak: about a minute; cargo test --release --test soak -- --ignored"]
fn fifteen_hundred_buoyancy_steps_keep_memory_flat() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let ctx = context();
    let mut sim = scene::paper_scene(50, 1.0 / 60.0).unwrap();
    let mut solver = GpuSolver::new(&ctx, &sim.shapes, sim.bodies.len(), 32).unwrap();
    assert_flat("buoyancy, 50 bodies", 1500, |_| {
        sim.step(&mut solver).unwrap()
    });
    assert!(
        sim.bodies.iter().all(|b| b.rigid.position.is_finite()),
        "a body left the finite world"
    );
}
