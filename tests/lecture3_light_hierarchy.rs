//! Lecture 3, technique 3: the light hierarchy and its quadtree search on the GPU against
//! the CPU reference (f64), on the room scene with 16 x 16 VPLs and a 32 x 32 picture.
//!
//! Tolerances. Clusters: sums and weighted means of fp32 values, relative 1e-5 (four
//! children per level, 4 levels). Gathers: each term of the sum is computed to a few units of
//! fp32 rounding u = 2^-24 of its bound flux / (pi max(d, d_min)^2), and summing n terms adds
//! at most n u of the sum of those bounds S; so |GPU - CPU| <= (n + 16) u S per channel. The
//! tree search decides radius < theta d in fp32: pixels with a decision within 1e-4 (relative)
//! of the threshold may go the other way and are counted apart (they must stay few).

use classic_gpgpu::lecture3::light_hierarchy::clusters::{cpu_clusters, Cluster, ClusterLevel};
use classic_gpgpu::lecture3::light_hierarchy::gather::MIN_DISTANCE;
use classic_gpgpu::lecture3::light_hierarchy::light::{brute_force, tree_gather, Receiver};
use classic_gpgpu::lecture3::light_hierarchy::{Gather, IndirectLighting, Scene};
use common::context;
use glam::DVec3;

mod common;

const U: f64 = 1.0 / (1u64 << 24) as f64;
const VPLS: u32 = 16;

fn lighting() -> IndirectLighting {
    let l = IndirectLighting::new(&context(), Scene::room(), VPLS, 32, 32).unwrap();
    l.build_lights().unwrap();
    l.draw_receivers().unwrap();
    l
}

/// S: the sum of every light's bound flux / (pi max(d, d_min)^2) (per channel).
fn scale(r: &Receiver, lights: &[Cluster]) -> DVec3 {
    lights
        .iter()
        .filter(|l| l.weight > 0.0)
        .map(|l| {
            let d2 = l.position.as_dvec3().distance_squared(r.position);
            l.flux.as_dvec3() / (std::f64::consts::PI * d2.max((MIN_DISTANCE as f64).powi(2)))
        })
        .sum()
}

fn assert_close(gpu: [f32; 4], cpu: DVec3, tol: DVec3, what: &str) {
    for c in 0..3 {
        assert!(
            (gpu[c] as f64 - cpu[c]).abs() <= tol[c] + 1e-12,
            "{what}: channel {c}: GPU {} vs CPU {}, allowed {}",
            gpu[c],
            cpu[c],
            tol[c]
        );
    }
}

fn assert_cluster_close(g: &Cluster, c: &Cluster, what: &str) {
    let close = |a: f32, b: f32, scale: f32| (a - b).abs() <= 1e-5 * scale.max(1.0);
    let ok = close(g.position.x, c.position.x, 1.0)
        && close(g.position.y, c.position.y, 1.0)
        && close(g.position.z, c.position.z, 1.0)
        && close(g.radius, c.radius, 1.0)
        && (g.normal - c.normal).abs().max_element() <= 1e-5
        && (g.weight - c.weight).abs() <= 1e-5 * c.weight
        && (g.flux - c.flux).abs().max_element() <= 1e-5 * c.flux.max_element()
        && g.count == c.count;
    assert!(ok, "{what}: GPU {g:?} vs CPU {c:?}");
}

#[test]
fn the_gpu_hierarchy_equals_the_cpu_clustering_of_the_same_vpls() {
    let l = lighting();
    let gpu = l.clusters.read_levels().unwrap();
    assert_eq!(gpu.len() as u32, VPLS.trailing_zeros() + 1);
    // A VPL per texel that sees the room (most do; some look out of its open front).
    let vpls = &gpu[0].nodes;
    assert!(vpls
        .iter()
        .all(|v| v.count == (v.weight > 0.0) as u8 as f32));
    let lit = vpls.iter().filter(|v| v.weight > 0.0).count();
    assert!(lit * 10 >= vpls.len() * 9, "{lit} VPLs");
    let cpu = cpu_clusters(gpu[0].clone());
    for (level, (g, c)) in gpu.iter().zip(&cpu).enumerate().skip(1) {
        for (i, (gn, cn)) in g.nodes.iter().zip(&c.nodes).enumerate() {
            assert_cluster_close(gn, cn, &format!("level {level} node {i}"));
        }
    }
    let root = &gpu.last().unwrap().nodes[0];
    assert_eq!(root.count, lit as f32);
    // Every VPL lies within its root's radius.
    for v in vpls.iter().filter(|v| v.weight > 0.0) {
        assert!(v.position.distance(root.position) <= root.radius * (1.0 + 1e-5));
    }
    // And the atlases the gathers read hold the same levels.
    assert_eq!(l.clusters.read_atlas_levels().unwrap(), gpu);
}

fn receivers_and_levels(l: &IndirectLighting) -> (Vec<Option<Receiver>>, Vec<ClusterLevel>) {
    (
        l.gbuffer.receivers().unwrap(),
        l.clusters.read_atlas_levels().unwrap(),
    )
}

#[test]
fn brute_force_gather_equals_the_cpu_sum() {
    let l = lighting();
    let (receivers, levels) = receivers_and_levels(&l);
    l.gather(Gather::BruteForce).unwrap();
    let gpu = l.gathers.read().unwrap();
    let n = (VPLS * VPLS) as f64;
    let mut lit = 0;
    for (i, r) in receivers.iter().enumerate() {
        let Some(r) = r else {
            assert_eq!(gpu[i], [0.0; 4], "pixel {i}: no receiver");
            continue;
        };
        let cpu = brute_force(r, &levels[0], MIN_DISTANCE as f64);
        let tol = (n + 16.0) * U * scale(r, &levels[0].nodes);
        assert_close(gpu[i], cpu, tol, &format!("pixel {i}"));
        lit += (cpu.max_element() > 0.0) as usize;
    }
    assert!(lit > 800, "most receivers get indirect light: {lit}");
}

#[test]
fn tree_search_with_theta_0_visits_every_vpl_and_equals_brute_force() {
    let l = lighting();
    let (receivers, levels) = receivers_and_levels(&l);
    l.gather(Gather::BruteForce).unwrap();
    let brute = l.gathers.read().unwrap();
    l.gather(Gather::tree(0.0).unwrap()).unwrap();
    let tree = l.gathers.read().unwrap();
    let n = (VPLS * VPLS) as f64;
    // The root, and the four children of every node above level 0 that holds light.
    let every_node = 1 + 4 * levels[1..]
        .iter()
        .flat_map(|l| &l.nodes)
        .filter(|c| c.weight > 0.0)
        .count() as u32;
    for (i, r) in receivers.iter().enumerate() {
        let Some(r) = r else { continue };
        let cpu = tree_gather(r, &levels, 0.0, MIN_DISTANCE as f64);
        assert_eq!(cpu.visited, every_node);
        assert_eq!(tree[i][3] as u32, cpu.visited, "pixel {i}: nodes visited");
        let tol = 2.0 * (n + 16.0) * U * scale(r, &levels[0].nodes);
        let b = DVec3::new(brute[i][0] as f64, brute[i][1] as f64, brute[i][2] as f64);
        assert_close(
            tree[i],
            b,
            tol,
            &format!("pixel {i}, tree against brute force"),
        );
    }
}

#[test]
fn tree_search_equals_the_cpu_search_for_a_positive_theta() {
    let l = lighting();
    let (receivers, levels) = receivers_and_levels(&l);
    let theta = 0.4;
    l.gather(Gather::tree(theta).unwrap()).unwrap();
    let gpu = l.gathers.read().unwrap();
    let (mut judged, mut marginal) = (0, 0);
    for (i, r) in receivers.iter().enumerate() {
        let Some(r) = r else { continue };
        let cpu = tree_gather(r, &levels, theta as f64, MIN_DISTANCE as f64);
        if cpu.margin < 1e-4 {
            marginal += 1;
            continue;
        }
        judged += 1;
        assert_eq!(gpu[i][3] as u32, cpu.visited, "pixel {i}: nodes visited");
        assert!(
            cpu.visited < 200,
            "pixel {i}: theta {theta} prunes the tree"
        );
        let all: Vec<Cluster> = levels.iter().flat_map(|l| l.nodes.clone()).collect();
        let tol = (cpu.visited as f64 + 16.0) * U * scale(r, &all);
        assert_close(gpu[i], cpu.irradiance, tol, &format!("pixel {i}"));
    }
    assert!(
        marginal * 20 <= judged,
        "{marginal} marginal pixels of {judged}"
    );
}

#[test]
fn a_larger_theta_visits_fewer_nodes_and_errs_more() {
    let l = lighting();
    l.gather(Gather::BruteForce).unwrap();
    let exact = l.gathers.read().unwrap();
    let run = |theta: f32| {
        l.gather(Gather::tree(theta).unwrap()).unwrap();
        let out = l.gathers.read().unwrap();
        let (mut err, mut norm, mut visited) = (0.0f64, 0.0f64, 0.0f64);
        for (g, e) in out.iter().zip(&exact) {
            for c in 0..3 {
                err += (g[c] as f64 - e[c] as f64).powi(2);
                norm += (e[c] as f64).powi(2);
            }
            visited += g[3] as f64;
        }
        ((err / norm).sqrt(), visited)
    };
    let (e_small, v_small) = run(0.2);
    let (e_large, v_large) = run(1.0);
    assert!(v_large < v_small, "{v_large} vs {v_small}");
    assert!(e_small < e_large, "{e_small} vs {e_large}");
    assert!(e_small < 0.05, "theta 0.2: relative RMS error {e_small}");
}

#[test]
fn bad_parameters_are_named() {
    let err = Gather::tree(f32::NAN).unwrap_err().to_string();
    assert!(err.contains("--theta") && err.contains("NaN"), "{err}");
    let err = Gather::tree(-1.0).unwrap_err().to_string();
    assert!(err.contains("--theta") && err.contains("range"), "{err}");
    let err = IndirectLighting::new(&context(), Scene::room(), 12, 8, 8)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("--vpls") && err.contains("power of two"),
        "{err}"
    );
}

#[test]
fn the_report_run_leaves_its_last_criterion_gathered_for_the_picture() {
    // The section's picture of the coarsest criterion shades what `light_run` left in the
    // gather target: it must be that criterion's gather, as a gather of its own draws it.
    use classic_gpgpu::report::lecture3::light_run;
    use classic_gpgpu::timing::Runs;
    let ctx = context();
    let (run, lighting, ()) =
        light_run(
            &ctx,
            VPLS,
            32,
            32,
            &[0.2, 1.5],
            Runs::exactly(2),
            |_| Ok(()),
        )
        .unwrap();
    assert_eq!(run.rows.len(), 2);
    let left = lighting.gathers.read().unwrap();
    lighting.gather(Gather::tree(1.5).unwrap()).unwrap();
    let again = lighting.gathers.read().unwrap();
    assert_eq!(left, again, "the target holds theta 1.5's gather");
    lighting.gather(Gather::tree(0.2).unwrap()).unwrap();
    let other = lighting.gathers.read().unwrap();
    assert_ne!(
        left, other,
        "the two criteria draw different gathers (the check can fail)"
    );
}
