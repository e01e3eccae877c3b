//! Lecture 3, the light hierarchy's other uses: normal-aware clustering, subsurface scattering
//! (the dipole summed over irradiance samples) and environment light (a sky as directional
//! lights), each GPU gather against its CPU reference (f64) on scenes made here, and the tree
//! search against the brute-force sum.
//!
//! Tolerances, as in `lecture3_light_hierarchy.rs`: each term of a sum is computed to a few
//! hundred units of fp32 rounding u = 2^-24 of a bound B of its size (exp, sqrt and divisions
//! of fp32 inputs: 512 u allowed), and summing n terms adds at most n u of the sum of the
//! bounds; so |GPU - CPU| <= (n + 512) u S, S the sum of every node's bound. Tree decisions
//! within 1e-4 (relative) of a threshold may go either way in fp32: those pixels are counted
//! apart and must stay few.

use classic_gpgpu::lecture3::light_hierarchy::clusters::{Cluster, ClusterLevel};
use classic_gpgpu::lecture3::light_hierarchy::environment::Sky;
use classic_gpgpu::lecture3::light_hierarchy::light::{
    brute_force_with, tree_gather_with, Criterion, Kernel, Receiver, VplKernel,
};
use classic_gpgpu::lecture3::light_hierarchy::model::{model_alone, model_triangles};
use classic_gpgpu::lecture3::light_hierarchy::normal_cone::{
    compare_clustering, relative_rms, MIN_COHERENCE,
};
use classic_gpgpu::lecture3::light_hierarchy::subsurface::Material;
use classic_gpgpu::lecture3::light_hierarchy::{gather::MIN_DISTANCE, Gather, IndirectLighting};
use classic_gpgpu::lecture3::light_hierarchy::{LightUse, Scene};
use classic_gpgpu::mesh::Mesh;
use common::context;
use glam::{DVec3, Vec3};

mod common;

const U: f64 = 1.0 / (1u64 << 24) as f64;

/// Per light, a bound of the size of what it gives `r` (per channel).
type Bound<'a> = &'a dyn Fn(&Receiver, &Cluster) -> DVec3;

fn vpl_bound(r: &Receiver, l: &Cluster) -> DVec3 {
    let d2 = l.position.as_dvec3().distance_squared(r.position);
    l.flux.as_dvec3() / (std::f64::consts::PI * d2.max((MIN_DISTANCE as f64).powi(2)))
}

/// Every gather of `lighting` with `gather` against the CPU's traversal with `kernel`: the
/// sums within (n + 512) u S, nodes visited equal; returns (judged, marginal) pixels.
fn gpu_equals_cpu(
    lighting: &IndirectLighting,
    gather: Gather,
    kernel: &impl Kernel,
    bound: Bound,
) -> (usize, usize) {
    let receivers = lighting.gbuffer.receivers().unwrap();
    let levels = lighting.clusters.read_atlas_levels().unwrap();
    lighting.gather(gather).unwrap();
    let gpu = lighting.gathers.read().unwrap();
    let all: Vec<Cluster> = levels
        .iter()
        .flat_map(|l| l.nodes.clone())
        .filter(|c| c.weight > 0.0)
        .collect();
    let (mut judged, mut marginal) = (0, 0);
    for (i, r) in receivers.iter().enumerate() {
        let Some(r) = r else {
            assert_eq!(gpu[i], [0.0; 4], "pixel {i}: no receiver");
            continue;
        };
        let (cpu, n) = match gather.criterion() {
            None => (
                brute_force_with(r, &levels[0], kernel),
                levels[0].nodes.len(),
            ),
            Some(criterion) => {
                let t = tree_gather_with(r, &levels, criterion, kernel);
                if t.margin < 1e-4 {
                    marginal += 1;
                    continue;
                }
                assert_eq!(gpu[i][3] as u32, t.visited, "pixel {i}: nodes visited");
                (t.irradiance, t.visited as usize)
            }
        };
        judged += 1;
        let s: DVec3 = all.iter().map(|l| bound(r, l)).sum();
        let tol = (n as f64 + 512.0) * U * s;
        for c in 0..3 {
            assert!(
                (gpu[i][c] as f64 - cpu[c]).abs() <= tol[c] + 1e-12,
                "pixel {i}, {gather:?}: channel {c}: GPU {} vs CPU {}, allowed {}",
                gpu[i][c],
                cpu[c],
                tol[c]
            );
        }
    }
    assert!(judged > 0, "no receiver was judged");
    assert!(
        marginal * 20 <= judged,
        "{marginal} marginal pixels of {judged}"
    );
    (judged, marginal)
}

fn room() -> IndirectLighting {
    let l = IndirectLighting::new(&context(), Scene::room(), 16, 32, 32).unwrap();
    l.build_lights().unwrap();
    l.draw_receivers().unwrap();
    l
}

#[test]
fn normal_aware_tree_search_equals_the_cpu_search() {
    let l = room();
    let kernel = VplKernel {
        min_distance: MIN_DISTANCE as f64,
    };
    for theta in [0.3, 0.8] {
        let gather = Gather::normal_aware(theta, MIN_COHERENCE).unwrap();
        gpu_equals_cpu(&l, gather, &kernel, &vpl_bound);
    }
}

/// The room's corners (walls meeting the floor and each other, the block's edges) are where
/// the fixed merge joins VPLs that face different ways.
#[test]
fn normal_aware_clustering_errs_no_more_than_the_fixed_merge_at_sharp_corners() {
    let l = room();
    let levels: Vec<ClusterLevel> = l.clusters.read_atlas_levels().unwrap();
    // The scene has clusters across surfaces: some level-1 node has children facing apart.
    let incoherent = levels[1]
        .nodes
        .iter()
        .filter(|c| c.weight > 0.0 && c.normal.length() < MIN_COHERENCE)
        .count();
    assert!(incoherent > 0, "no cluster straddles a corner");
    let rows = compare_clustering(&l, &[0.5, 1.0, 2.0], MIN_COHERENCE).unwrap();
    for r in &rows {
        assert!(
            r.normal_aware_error <= r.fixed_error,
            "theta {}: normal-aware {} against fixed {}",
            r.theta,
            r.normal_aware_error,
            r.fixed_error
        );
        assert!(r.normal_aware_lights >= r.fixed_lights);
        assert!(r.normal_aware_nodes >= r.fixed_nodes);
    }
    // With a loose theta the difference is real, not rounding.
    let loose = rows.last().unwrap();
    assert!(
        loose.normal_aware_error < 0.9 * loose.fixed_error,
        "{loose:?}"
    );
    // Coherence 0 is the fixed merge, pixel for pixel.
    l.gather(Gather::tree(1.0).unwrap()).unwrap();
    let fixed = l.gathers.read().unwrap();
    l.gather(Gather::normal_aware(1.0, 0.0).unwrap()).unwrap();
    assert_eq!(l.gathers.read().unwrap(), fixed);
    // And the CPU reference agrees that coherence refines: same receivers, more lights.
    let receivers = l.gbuffer.receivers().unwrap();
    let kernel = VplKernel {
        min_distance: MIN_DISTANCE as f64,
    };
    let more = receivers
        .iter()
        .flatten()
        .filter(|r| {
            let f = tree_gather_with(r, &levels, Criterion::theta(1.0), &kernel);
            let a = tree_gather_with(
                r,
                &levels,
                Criterion {
                    theta: 1.0,
                    min_coherence: MIN_COHERENCE as f64,
                },
                &kernel,
            );
            a.gathered > f.gathered
        })
        .count();
    assert!(more > 0);
}

/// A UV sphere of `rings x segments` quads (poles as fans), counter-clockwise outward.
fn sphere(rings: u32, segments: u32) -> Mesh {
    let mut positions = vec![Vec3::Y, -Vec3::Y];
    for i in 1..rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            positions.push(Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ));
        }
    }
    let at = |ring: u32, j: u32| 2 + (ring - 1) * segments + j % segments;
    let mut triangles = Vec::new();
    for j in 0..segments {
        triangles.push([0, at(1, j + 1), at(1, j)]);
        triangles.push([1, at(rings - 1, j), at(rings - 1, j + 1)]);
        for ring in 1..rings - 1 {
            let (a, b, c, d) = (
                at(ring, j),
                at(ring, j + 1),
                at(ring + 1, j + 1),
                at(ring + 1, j),
            );
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles)
}

fn ball(light_use: LightUse, side: u32) -> IndirectLighting {
    let albedo = if matches!(light_use, LightUse::Subsurface(_)) {
        Vec3::ONE
    } else {
        Vec3::splat(0.75)
    };
    let triangles = model_triangles(&sphere(8, 16), "test sphere", albedo).unwrap();
    let l = IndirectLighting::for_use(&context(), light_use, model_alone(triangles), side, 24, 24)
        .unwrap();
    l.build_lights().unwrap();
    l.draw_receivers().unwrap();
    l
}

/// A model alone is lit by a spot light whose frustum is fitted to it, so that the light's
/// image (subsurface scattering's irradiance samples) is spent on the model: a sphere's outline
/// fills a disc inscribed in the square image, pi/4 = 78.5% of it (less the fit's 2% margin
/// and the tessellation, whose outline lies inside the sphere's), and it reaches the image's
/// border.
#[test]
fn the_fitted_light_spends_its_image_on_the_model() {
    let side = 32;
    let l = ball(LightUse::subsurface(), side);
    let level0 = &l.clusters.read_levels().unwrap()[0];
    let lit = |x: u32, y: u32| level0.at(x, y).weight > 0.0;
    let count = (0..side)
        .flat_map(|y| (0..side).map(move |x| (x, y)))
        .filter(|&(x, y)| lit(x, y))
        .count();
    let share = count as f64 / (side * side) as f64;
    assert!(
        share > 0.65 && share < 0.79,
        "{count} of {} texels lit",
        side * side
    );
    // The widest vertex lies within the 2% margin (a third of a texel) of the border.
    let border = (0..side)
        .flat_map(|y| (0..side).map(move |x| (x, y)))
        .filter(|&(x, y)| x.min(y).min(side - 1 - x).min(side - 1 - y) < 2)
        .any(|(x, y)| lit(x, y));
    assert!(border, "the frustum is loose: nothing lit near its border");
}

/// Relative RMS error of the GPU tree search against the GPU brute force, and nodes visited.
fn tree_error(l: &IndirectLighting, theta: f32) -> (f64, f64) {
    l.gather(Gather::BruteForce).unwrap();
    let brute = l.gathers.read().unwrap();
    l.gather(Gather::tree(theta).unwrap()).unwrap();
    let tree = l.gathers.read().unwrap();
    let covered: Vec<bool> = brute.iter().map(|b| b[3] > 0.0).collect();
    let nodes = tree.iter().map(|t| t[3] as f64).sum::<f64>()
        / covered.iter().filter(|&&c| c).count() as f64;
    (relative_rms(&tree, &brute, &covered), nodes)
}

#[test]
fn the_dipole_matches_its_published_limits() {
    let d = Material::skin().dipole();
    // R_d integrates to the total diffuse reflectance, Jensen et al. eq. for R_d total:
    // (α'/2)(1 + e^(-4/3 A sqrt(3(1-α')))) e^(-sqrt(3(1-α'))), integrated here numerically.
    let m = Material::skin();
    let eta = m.eta as f64;
    let f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    let a = (1.0 + f_dr) / (1.0 - f_dr);
    let steps = 200_000;
    let r_max = 2.0;
    let dr = r_max / steps as f64;
    let numeric: DVec3 = (0..steps)
        .map(|i| {
            let r = (i as f64 + 0.5) * dr;
            d.rd(r) * (2.0 * std::f64::consts::PI * r * dr)
        })
        .sum();
    for c in 0..3 {
        let alpha = d.alpha_prime[c];
        let s = (3.0 * (1.0 - alpha)).sqrt();
        let total = 0.5 * alpha * (1.0 + (-4.0 / 3.0 * a * s).exp()) * (-s).exp();
        assert!(
            (numeric[c] - total).abs() <= 1e-3 * total,
            "channel {c}: integral of R_d {} against the closed form {total}",
            numeric[c]
        );
    }
}

#[test]
fn subsurface_gathers_equal_the_cpu_and_the_tree_approaches_the_brute_force() {
    let l = ball(LightUse::subsurface(), 16);
    let kernel = l.light_use.kernel();
    let dipole = match l.light_use {
        LightUse::Subsurface(m) => m.dipole(),
        _ => unreachable!(),
    };
    let bound = move |r: &Receiver, c: &Cluster| -> DVec3 {
        c.flux.as_dvec3() * dipole.rd(c.position.as_dvec3().distance(r.position))
    };
    gpu_equals_cpu(&l, Gather::BruteForce, &kernel, &bound);
    gpu_equals_cpu(&l, Gather::tree(0.5).unwrap(), &kernel, &bound);
    // Theta 0 is the brute force; a small theta stays within 5% (RMS) of it and gathers fewer
    // nodes than there are samples; a larger one errs more.
    let (exact, _) = tree_error(&l, 0.0);
    assert!(exact < 1e-5, "theta 0: {exact}");
    let (fine, fine_nodes) = tree_error(&l, 0.25);
    let (coarse, coarse_nodes) = tree_error(&l, 1.0);
    assert!(fine < 0.05, "theta 0.25: relative RMS error {fine}");
    assert!(
        coarse > fine && coarse_nodes < fine_nodes,
        "{coarse} {coarse_nodes} {fine_nodes}"
    );
    assert!(fine_nodes < 256.0, "{fine_nodes} nodes");
}

#[test]
fn sky_lights_cover_the_sphere_and_environment_gathers_equal_the_cpu() {
    let sky = Sky::default();
    // The lat-long grid's solid angles sum to 4π (midpoint rule, error O(1/N²)).
    let lights = sky.lights(16);
    let total: f64 = lights
        .nodes
        .iter()
        .map(|l| {
            let w = l.position.as_dvec3();
            l.flux.x as f64 / sky.radiance(w).x
        })
        .sum();
    let four_pi = 4.0 * std::f64::consts::PI;
    assert!((total - four_pi).abs() < 0.01 * four_pi, "{total}");
    let l = ball(LightUse::environment(), 16);
    assert_eq!(l.clusters.read_levels().unwrap()[0], lights);
    let kernel = l.light_use.kernel();
    let bound = |_: &Receiver, c: &Cluster| c.flux.as_dvec3();
    gpu_equals_cpu(&l, Gather::BruteForce, &kernel, &bound);
    gpu_equals_cpu(&l, Gather::tree(0.5).unwrap(), &kernel, &bound);
    gpu_equals_cpu(&l, Gather::tree(1.0).unwrap(), &kernel, &bound);
    // With theta <= 1 no cluster straddles a receiver's horizon: only the sky's colour varying
    // inside a cluster errs, and the error stays small; theta 0 is the brute force.
    let (exact, _) = tree_error(&l, 0.0);
    assert!(exact < 1e-5, "theta 0: {exact}");
    let (one, nodes) = tree_error(&l, 1.0);
    assert!(one < 0.05, "theta 1: relative RMS error {one}");
    assert!(nodes < 256.0, "{nodes} nodes");
}

#[test]
fn a_bad_scene_is_a_clear_error_and_exposure_changes_only_the_picture() {
    let dir = std::env::temp_dir().join(format!("lecture3_light_uses_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nf 1 2 7\n").unwrap();
    let flat = dir.join("line.obj");
    std::fs::write(&flat, "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").unwrap();
    let missing = dir.join("missing.obj");
    for (path, says) in [
        (&bad, "vertices"),
        (&flat, "zero area"),
        (&missing, "cannot read"),
    ] {
        let out = common::classic_gpgpu(&[
            "lecture3",
            "light",
            "--mode",
            "sss",
            "--scene",
            path.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{path:?} accepted");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(
            stderr.contains("--scene") && stderr.contains(path.to_str().unwrap()),
            "{stderr}"
        );
        assert!(stderr.contains(says), "{stderr}");
    }
    // A small model of the test's own, at two exposures: the numbers stay, the picture not.
    let model = dir.join("ball.obj");
    classic_gpgpu::mesh::obj::write_obj(&sphere(6, 12), &model).unwrap();
    let run = |stops: &str, name: &str| {
        let npy = dir.join(name);
        let png = dir.join(format!("{name}.png"));
        let v = common::json_of(&[
            "lecture3",
            "light",
            "--mode",
            "environment",
            "--scene",
            model.to_str().unwrap(),
            "--vpls",
            "8",
            "--size",
            "16",
            "--theta",
            "0.5",
            "--exposure",
            stops,
            "--npy",
            npy.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
            "--json",
        ]);
        let rel = v["light"]["run"]["rows"][0]["relative_rms_error"]
            .as_f64()
            .unwrap();
        assert!(rel.is_finite() && rel < 0.1, "{v}");
        let (shape, data) = classic_gpgpu::files::read_npy(&npy.join("irradiance.npy")).unwrap();
        assert_eq!(shape, vec![16, 16, 3]);
        (data, std::fs::read(&png).unwrap())
    };
    let (npy0, png0) = run("0", "a");
    let (npy2, png2) = run("-2", "b");
    assert_eq!(npy0, npy2);
    assert_ne!(png0, png2);
    let _ = std::fs::remove_dir_all(&dir);
}
