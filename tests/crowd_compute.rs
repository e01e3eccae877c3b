//! Paper 2's compute formulation (OpenGL 4.3): skinning into a storage buffer that the
//! drawing pass reads directly, against f64 CPU skinning and the classic two-pass
//! (pass 1 + render-to-VBO) vertices, with the classic path's tolerance (16 ulp of the
//! coordinate's magnitude; normals 1e-5), and the image against the classic two-pass image.
//! Below 4.3 (softpipe): the clear error, and the classic two-pass still runs.

use classic_gpgpu::crowd::character::Instances;
use classic_gpgpu::crowd::compute::ComputeCrowd;
use classic_gpgpu::crowd::cpu_skinning;
use classic_gpgpu::crowd::culling::FramePlan;
use classic_gpgpu::crowd::renderer::{CrowdRenderer, Method};
use classic_gpgpu::crowd::scene::{self, SKY};
use classic_gpgpu::crowd::{CharacterModel, ModelKind};
use classic_gpgpu::gl::Rect;
use common::compute_context;
use glam::{DAffine3, DQuat, DVec3};

mod common;

fn scattered(n: usize) -> (Vec<DAffine3>, Vec<f64>) {
    (0..n)
        .map(|i| {
            let t = i as f64;
            let place = DAffine3::from_rotation_translation(
                DQuat::from_rotation_y(0.9 * t - 1.0),
                DVec3::new(
                    13.0 * (t * 1.7).sin() * t.sqrt(),
                    0.0,
                    -11.0 * (t * 0.6).cos() * t.sqrt(),
                ),
            );
            (place, 0.137 * t + 0.05 * t * t)
        })
        .unzip()
}

fn tolerance(scale: f64) -> f64 {
    16.0 * f32::EPSILON as f64 * (1.0 + scale)
}

#[test]
fn compute_skinning_matches_cpu_and_the_classic_two_pass() {
    let (ctx, compute) = compute_context();
    let (models, phases) = scattered(200);
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind).unwrap();
        let mut classic = CrowdRenderer::new(&ctx, model.clone()).unwrap();
        if !compute {
            let err = ComputeCrowd::new(&ctx, model).err().unwrap().to_string();
            assert!(
                err.contains("paper 2") && err.contains("needs OpenGL 4.3"),
                "{err}"
            );
            assert_eq!(
                classic.skin_to_vbo(2, &instances, &[3, 1]).unwrap().len(),
                2
            );
            continue;
        }
        let mut modern = ComputeCrowd::new(&ctx, model.clone()).unwrap();
        let many: Vec<usize> = (0..200).rev().collect();
        for (lod, ids) in [(0, vec![6, 0, 3, 5, 1]), (2, many)] {
            let now = modern.skin(lod, &instances, &ids).unwrap();
            let then = classic.skin_to_vbo(lod, &instances, &ids).unwrap();
            assert_eq!(now.len(), ids.len());
            let mesh = &model.lods[lod];
            for (slot, &id) in ids.iter().enumerate().step_by(7) {
                let pose = model.clip.sample(&model.skeleton, phases[id]);
                let bones = model.skeleton.skinning_matrices(&pose, models[id]);
                let cpu = cpu_skinning::skin(mesh, &bones);
                let (positions, normals) = &now[slot];
                let (classic_positions, _) = &then[slot];
                for v in 0..mesh.vertex_count() {
                    let p = positions[v];
                    let q = cpu.positions[v];
                    let gpu = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
                    let tol = tolerance(q.abs().max_element());
                    let err = (gpu - q).abs().max_element();
                    assert!(
                        err <= tol,
                        "{kind:?} LOD {lod} char {id} vertex {v}: {p:?} vs {q}"
                    );
                    let c = classic_positions[v];
                    let vs_classic = (0..3)
                        .map(|k| (p[k] as f64 - c[k] as f64).abs())
                        .fold(0.0, f64::max);
                    assert!(
                        vs_classic <= 2.0 * tol,
                        "{kind:?} vertex {v}: {p:?} vs {c:?}"
                    );
                    assert_eq!(p[3], 1.0);
                    let n = normals[v];
                    let nerr = (DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64) - cpu.normals[v])
                        .length();
                    assert!(
                        nerr < 1e-5,
                        "{kind:?} normal {v}: {n:?} vs {}",
                        cpu.normals[v]
                    );
                }
            }
        }
    }
}

#[test]
fn compute_draws_the_same_image_as_the_classic_two_pass() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let (w, h) = (192, 144);
    let target = scene::scene_target(&ctx, w, h).unwrap();
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind).unwrap();
        let mut classic = CrowdRenderer::new(&ctx, model.clone()).unwrap();
        let mut modern = ComputeCrowd::new(&ctx, model).unwrap();
        let scene = scene::table1_scene(kind, 12, w as f32 / h as f32, 3);
        let (models, phases) = scene::placements(&scene.crowd);
        let instances = Instances {
            models: &models,
            phases: &phases,
        };
        let mut plan = FramePlan::default();
        plan.lods[0] = (0..models.len()).collect();
        scene::clear(&target).unwrap();
        classic
            .render(
                &target,
                &scene.camera,
                &instances,
                &plan,
                Method::TwoPass,
                false,
            )
            .unwrap();
        let then = target.read_u8(0, Rect::sized(w, h)).unwrap();
        scene::clear(&target).unwrap();
        let stats = modern
            .render(&target, &scene.camera, &instances, &plan, true)
            .unwrap();
        assert_eq!(stats.skinned, models.len());
        assert_eq!(stats.pass1_draws, 1, "one skinning dispatch for the LOD");
        let now = target.read_u8(0, Rect::sized(w, h)).unwrap();
        let sky = SKY.map(|c| (c * 255.0).round() as i32);
        let covered = now
            .chunks(4)
            .filter(|p| (0..3).any(|k| (p[k] as i32 - sky[k]).abs() > 1))
            .count();
        assert!(covered > (w * h) as usize / 100, "{kind:?}: nothing drawn");
        let differing = then
            .chunks(4)
            .zip(now.chunks(4))
            .filter(|(a, b)| {
                a.iter()
                    .zip(b.iter())
                    .any(|(x, y)| (*x as i32 - *y as i32).abs() > 2)
            })
            .count();
        eprintln!("{kind:?}: {differing} of {} pixels differ", w * h);
        assert!(
            differing <= (w * h) as usize / 500,
            "{kind:?}: {differing} pixels differ"
        );
        // Sprites are the classic renderer's: asking for them is a clear error.
        plan.sprites = vec![0];
        let err = modern
            .render(&target, &scene.camera, &instances, &plan, false)
            .unwrap_err()
            .to_string();
        assert!(err.contains("sprites"), "{err}");
    }
}
