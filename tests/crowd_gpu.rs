//! Paper 2 on a real headless context: pass 1 + render-to-VBO against the f64 CPU
//! reference, both skinning methods against each other, sprites, the CLI's errors.

use classic_gpgpu::crowd::character::Instances;
use classic_gpgpu::crowd::cpu_skinning;
use classic_gpgpu::crowd::culling::{plan_frame, Camera, FramePlan};
use classic_gpgpu::crowd::renderer::{CrowdRenderer, Method};
use classic_gpgpu::crowd::scene::{self, SKY};
use classic_gpgpu::crowd::sprites::{frame_row, view_column, FRAMES, VIEWS};
use classic_gpgpu::crowd::{CharacterModel, LodPolicy, ModelKind};
use classic_gpgpu::gl::Rect;
use common::{classic_gpgpu, context};
use glam::{DAffine3, DQuat, DVec3, Vec3};

mod common;

/// Characters scattered up to ~40 m from the origin, each turned and at its own phase.
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

/// fp32 bound for a skinned coordinate of magnitude up to `scale`: the f32 matrix entries,
/// the bind-pose vertex and the ~16 multiply-adds of the blend each round at 2^-24
/// relative; 16 ulp (f32::EPSILON = 2^-23) of the magnitude covers them with margin.
fn tolerance(scale: f64) -> f64 {
    16.0 * f32::EPSILON as f64 * (1.0 + scale)
}

#[test]
fn pass1_vbo_matches_cpu_linear_blend_skinning_in_f64() {
    let ctx = context();
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind).unwrap();
        let mut renderer = CrowdRenderer::new(&ctx, model.clone()).unwrap();
        let (models, phases) = scattered(300);
        let instances = Instances {
            models: &models,
            phases: &phases,
        };
        // A few characters, out of order (slot s holds character ids[s]), at two LODs;
        // then 300 characters, which fill three blocks of 128-character rows.
        let many: Vec<usize> = (0..300).rev().collect();
        for (lod, ids, checked) in [
            (0, vec![6, 0, 3, 5, 1], vec![0, 1, 2, 3, 4]),
            (2, vec![6, 0, 3, 5, 1], vec![0, 1, 2, 3, 4]),
            (2, many, vec![0, 1, 127, 128, 200, 255, 256, 299]),
        ] {
            let gpu = renderer.skin_to_vbo(lod, &instances, &ids).unwrap();
            let worst = assert_matches_cpu(&model, lod, &instances, &ids, &gpu, &checked);
            eprintln!(
                "{kind:?} LOD {lod}, {} characters: worst error {worst:.3} of the tolerance",
                ids.len()
            );
        }
    }
}

/// Checks the GPU-skinned vertices `gpu` (slot s holds character `ids[s]`) of the slots
/// `checked` against f64 CPU skinning; returns the worst error as a share of the tolerance.
fn assert_matches_cpu(
    model: &CharacterModel,
    lod: usize,
    instances: &Instances,
    ids: &[usize],
    gpu: &[classic_gpgpu::crowd::render_to_vbo::SkinnedColumn],
    checked: &[usize],
) -> f64 {
    let kind = model.kind;
    assert_eq!(gpu.len(), ids.len());
    let mesh = &model.lods[lod];
    let mut worst: f64 = 0.0;
    for &slot in checked {
        let id = ids[slot];
        let pose = model.clip.sample(&model.skeleton, instances.phases[id]);
        let bones = model
            .skeleton
            .skinning_matrices(&pose, instances.models[id]);
        let cpu = cpu_skinning::skin(mesh, &bones);
        let (positions, normals) = &gpu[slot];
        assert_eq!(positions.len(), mesh.vertex_count());
        for v in 0..mesh.vertex_count() {
            let p = positions[v];
            let q = cpu.positions[v];
            let err = (DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) - q)
                .abs()
                .max_element();
            let tol = tolerance(q.abs().max_element());
            assert!(
                err <= tol,
                "{kind:?} LOD {lod} character {id} vertex {v}: {p:?} vs {q} (err {err:e} > {tol:e})"
            );
            assert_eq!(p[3], 1.0);
            worst = worst.max(err / tol);
            let n = normals[v];
            let m = cpu.normals[v];
            let nerr = (DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64) - m).length();
            // Unit normals: a few ulp after the blend and the normalisation.
            assert!(nerr < 1e-5, "{kind:?} LOD {lod} normal {v}: {n:?} vs {m}");
        }
    }
    worst
}

#[test]
fn a_crowd_beyond_one_batch_is_skinned_in_several_draws_that_match_cpu_skinning() {
    // The paper skins every character in one draw; here one draw holds at most what a
    // render target does (3,712 soldiers at LOD 0 on 16384-texel targets), and a larger
    // crowd is split into batches. A small forced limit runs that path without allocating
    // targets of the largest size: 45 characters in batches of 16 (16 + 16 + 13), the
    // last batch partly filled and its target's rows unevenly used.
    let ctx = context();
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind).unwrap();
        let mut renderer = CrowdRenderer::new(&ctx, model.clone()).unwrap();
        let natural = renderer.batch_limit(0);
        renderer.set_batch_limit(Some(16));
        assert_eq!(renderer.batch_limit(0), 16);
        let (models, phases) = scattered(60);
        let instances = Instances {
            models: &models,
            phases: &phases,
        };
        // Out of order, so a batch that took the wrong slice of matrices would show.
        let ids: Vec<usize> = (0..45).map(|i| (i * 17 + 5) % 60).collect();
        for lod in [0, 2] {
            let gpu = renderer.skin_to_vbo(lod, &instances, &ids).unwrap();
            let every: Vec<usize> = (0..ids.len()).collect();
            let worst = assert_matches_cpu(&model, lod, &instances, &ids, &gpu, &every);
            eprintln!("{kind:?} LOD {lod}, 45 characters in batches of 16: worst {worst:.3}");
        }
        // Whole frames: three pass-1 draws, one image equal to the single-batch one.
        let (w, h) = (160, 120);
        let target = scene::scene_target(&ctx, w, h).unwrap();
        let scene = scene::table1_scene(kind, 45, w as f32 / h as f32, 5);
        let frame = |renderer: &mut CrowdRenderer| {
            scene::clear(&target).unwrap();
            let (stats, _) =
                scene::render_frame(renderer, &target, &scene, Method::TwoPass, false).unwrap();
            (stats, target.read_u8(0, Rect::sized(w, h)).unwrap())
        };
        let (batched, batched_image) = frame(&mut renderer);
        assert_eq!(batched.pass1_draws, 3, "{kind:?}");
        assert_eq!(batched.skinned, 45);
        renderer.set_batch_limit(None);
        assert_eq!(renderer.batch_limit(0), natural);
        let (single, single_image) = frame(&mut renderer);
        assert_eq!(single.pass1_draws, 1, "{kind:?}");
        assert!(
            1.0 - sky_fraction(&single_image) > 0.01,
            "{kind:?}: the crowd is not in view"
        );
        assert_eq!(
            batched_image, single_image,
            "{kind:?}: batches of 16 draw another image than one batch"
        );
    }
}

fn plan_all(n: usize, lod0: bool) -> FramePlan {
    let mut plan = FramePlan::default();
    if lod0 {
        plan.lods[0] = (0..n).collect();
    }
    plan
}

fn sky_fraction(pixels: &[u8]) -> f64 {
    let sky = SKY.map(|c| (c * 255.0).round() as i32);
    let is_sky = |p: &[u8]| (0..3).all(|k| (p[k] as i32 - sky[k]).abs() <= 1);
    pixels.chunks(4).filter(|p| is_sky(p)).count() as f64 / (pixels.len() / 4) as f64
}

#[test]
fn both_methods_render_the_same_image() {
    let ctx = context();
    let (w, h) = (192, 144);
    let target = scene::scene_target(&ctx, w, h).unwrap();
    for kind in ModelKind::ALL {
        let model = CharacterModel::build(kind).unwrap();
        let mut renderer = CrowdRenderer::new(&ctx, model).unwrap();
        let scene = scene::table1_scene(kind, 12, w as f32 / h as f32, 3);
        let mut images = Vec::new();
        for method in [Method::TwoPass, Method::VertexShader] {
            target.clear_colors(SKY).unwrap();
            target.clear_depth_stencil(1.0, 0).unwrap();
            scene::render_frame(&mut renderer, &target, &scene, method, false).unwrap();
            images.push(target.read_u8(0, Rect::sized(w, h)).unwrap());
        }
        let covered = 1.0 - sky_fraction(&images[0]);
        assert!(
            covered > 0.01,
            "{kind:?}: characters cover only {covered:.3} of the image"
        );
        // Same positions up to fp32 rounding: at most a few edge pixels may flip.
        let differing = images[0]
            .chunks(4)
            .zip(images[1].chunks(4))
            .filter(|(a, b)| {
                a.iter()
                    .zip(b.iter())
                    .any(|(x, y)| (*x as i32 - *y as i32).abs() > 2)
            })
            .count();
        let limit = (w * h) as usize / 500;
        eprintln!(
            "{kind:?}: {differing} of {} pixels differ between the methods",
            w * h
        );
        assert!(
            differing <= limit,
            "{kind:?}: {differing} pixels differ (limit {limit})"
        );
        // The comparison can fail: the same crowd half a cycle later looks different.
        let (models, mut phases) = scene::placements(&scene.crowd);
        phases.iter_mut().for_each(|p| *p += 0.5);
        target.clear_colors(SKY).unwrap();
        target.clear_depth_stencil(1.0, 0).unwrap();
        let plan = plan_all(models.len(), true);
        renderer
            .render(
                &target,
                &scene.camera,
                &Instances {
                    models: &models,
                    phases: &phases,
                },
                &plan,
                Method::TwoPass,
                false,
            )
            .unwrap();
        let later = target.read_u8(0, Rect::sized(w, h)).unwrap();
        let changed = images[0]
            .chunks(4)
            .zip(later.chunks(4))
            .filter(|(a, b)| a != b)
            .count();
        assert!(
            changed > 3 * limit,
            "{kind:?}: animation changed only {changed} pixels"
        );
    }
}

#[test]
fn lod_culling_and_sprites_draw_what_the_plan_says() {
    let ctx = context();
    let (w, h) = (160, 120);
    let target = scene::scene_target(&ctx, w, h).unwrap();
    let model = CharacterModel::build(ModelKind::Soldier).unwrap();
    let mut renderer = CrowdRenderer::new(&ctx, model.clone()).unwrap();
    let camera = Camera {
        eye: Vec3::new(0.0, 1.0, 0.0),
        target: Vec3::new(0.0, 1.0, 10.0),
        fov_y: 40f32.to_radians(),
        aspect: w as f32 / h as f32,
        near: 0.1,
        far: 300.0,
    };
    let at = |x: f64, z: f64| DAffine3::from_translation(DVec3::new(x, 0.0, z));
    // LOD 0, LOD 1, LOD 2, a sprite, and one behind the eye. Distances are scaled down
    // (with the thresholds) so that every level is several pixels tall at 160x120.
    let models = [
        at(-2.0, 5.0),
        at(2.0, 9.0),
        at(-3.0, 14.0),
        at(0.0, 22.0),
        at(0.0, -10.0),
    ];
    let phases = [0.1, 0.2, 0.3, 0.4, 0.5];
    let policy = LodPolicy {
        mesh_until: [7.0, 11.0],
        sprites_beyond: Some(18.0),
    };
    let plan = plan_frame(
        &models,
        model.bound_centre,
        model.bound_radius,
        &camera,
        Some(&policy),
        true,
    );
    assert_eq!(plan.lods, [vec![0], vec![1], vec![2]]);
    assert_eq!((plan.sprites.clone(), plan.culled), (vec![3], 1));
    target.clear_colors(SKY).unwrap();
    target.clear_depth_stencil(1.0, 0).unwrap();
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    let stats = renderer
        .render(&target, &camera, &instances, &plan, Method::TwoPass, true)
        .unwrap();
    assert_eq!((stats.skinned, stats.sprites), (3, 1));
    assert_eq!(stats.triangles, 1084 + 544 + 312);
    let pixels = target.read_u8(0, Rect::sized(w, h)).unwrap();
    // Each drawn character covers pixels around where its bounding-sphere centre projects.
    let vp = camera.view_projection();
    for (i, m) in models.iter().enumerate().take(4) {
        let c = m.transform_point3(model.bound_centre.as_dvec3()).as_vec3();
        let ndc = vp.project_point3(c);
        let (px, py) = (
            ((ndc.x + 1.0) * 0.5 * w as f32) as i32,
            ((ndc.y + 1.0) * 0.5 * h as f32) as i32,
        );
        let found = (-3..=3)
            .flat_map(|dy| (-3..=3).map(move |dx| (px + dx, py + dy)))
            .any(|(x, y)| {
                let k = 4 * (y as usize * w as usize + x as usize);
                (x >= 0 && y >= 0 && x < w as i32 && y < h as i32)
                    && sky_fraction(&pixels[k..k + 4]) == 0.0
            });
        assert!(
            found,
            "character {i} (level {:?}) not drawn near pixel ({px}, {py})",
            policy.select(c.distance(camera.eye))
        );
    }
}

#[test]
fn sprite_tiles_follow_view_direction_and_phase() {
    // Facing the eye (eye straight ahead along the heading): column 0.
    assert_eq!(view_column(0.0, DVec3::Z), 0);
    // Turned a quarter to the left of the eye direction: a quarter of the columns.
    assert_eq!(
        view_column(std::f64::consts::FRAC_PI_2, DVec3::Z),
        VIEWS / 4
    );
    assert_eq!(
        view_column(-std::f64::consts::FRAC_PI_2, DVec3::Z),
        3 * VIEWS / 4
    );
    assert_eq!(view_column(0.0, -DVec3::Z), VIEWS / 2);
    assert_eq!(frame_row(0.0), 0);
    assert_eq!(frame_row(2.999), FRAMES - 1);
    assert_eq!(frame_row(-0.25), 3 * FRAMES / 4);
}

#[test]
fn the_atlas_holds_every_view_and_phase() {
    let ctx = context();
    let model = CharacterModel::build(ModelKind::Horse).unwrap();
    let renderer = CrowdRenderer::new(&ctx, model).unwrap();
    let atlas = renderer.sprites().atlas();
    let pixels = atlas.download_u8().unwrap();
    let tile = atlas.width() / VIEWS;
    for row in 0..FRAMES {
        for column in 0..VIEWS {
            let opaque = (0..tile * tile)
                .filter(|k| {
                    let (x, y) = (column * tile + k % tile, row * tile + k / tile);
                    pixels[4 * (y * atlas.width() + x) as usize + 3] > 0
                })
                .count();
            assert!(
                opaque > (tile * tile / 50) as usize,
                "tile ({column}, {row}) is nearly empty"
            );
        }
    }
}

#[test]
fn crowd_command_reports_json_and_rejects_bad_input() {
    // One name per process, gone first: an existing --png is now refused without --force.
    let png = std::env::temp_dir().join(format!(
        "classic_gpgpu_crowd_test_{}.png",
        std::process::id()
    ));
    let _ = std::fs::remove_file(&png);
    let out = classic_gpgpu(&[
        "crowd",
        "--model",
        "horse",
        "--characters",
        "8",
        "--frames",
        "1",
        "--size",
        "96x64",
        "--method",
        "vertex-shader",
        "--json",
        "--png",
        png.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["run"]["characters"], 8);
    assert_eq!(v["run"]["method"], "vertex-shader");
    assert!(v["run"]["fps"].as_f64().unwrap() > 0.0);
    assert!(png.exists());
    let again = classic_gpgpu(&[
        "crowd",
        "--characters",
        "8",
        "--frames",
        "1",
        "--size",
        "96x64",
        "--png",
        png.to_str().unwrap(),
    ]);
    assert!(
        !again.status.success() && String::from_utf8_lossy(&again.stderr).contains("--force"),
        "an existing --png was replaced without --force"
    );
    let _ = std::fs::remove_file(&png);
    for (args, needle) in [
        (vec!["crowd", "--characters", "0"], "--characters"),
        (vec!["crowd", "--size", "640"], "WxH"),
        (vec!["crowd", "--model", "dragon"], "dragon"),
        // Beyond any renderer's texture side: refused by the option's range (a size within it
        // but beyond this renderer's viewport is refused when the context is made).
        (vec!["crowd", "--size", "99999x10"], "from 1 to 32768"),
    ] {
        let out = classic_gpgpu(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(
            err.contains(needle) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn crowd_bench_quick_reports_table1_beside_the_paper() {
    // A folder of this run's own: the bench refuses a folder of files it did not write.
    let out_dir = std::env::temp_dir().join(format!(
        "classic_gpgpu_crowd_bench_test-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&out_dir);
    let out = classic_gpgpu(&[
        "crowd-bench",
        "--quick",
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let section: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(section["id"], "paper2");
    let table1 = &section["tables"][0];
    assert_eq!(
        table1["rows"].as_array().unwrap().len(),
        3,
        "quick mode: n = 1, 16, 64"
    );
    // The paper's numbers sit beside ours: n = 16, soldier VS paper = 580.
    assert_eq!(table1["rows"][1][0], "16");
    assert_eq!(table1["rows"][1][1], "580");
    let measured: f64 = table1["rows"][1][2].as_str().unwrap().parse().unwrap();
    assert!(measured > 0.0);
    let claims = section["claims"].as_array().unwrap();
    assert_eq!(claims.len(), 4);
    // The single-draw claim states the limit of one draw on this renderer.
    let single = claims
        .iter()
        .find(|c| c["claim"].as_str().unwrap().contains("single draw call"))
        .expect("the single-draw claim");
    let results = &section["results"];
    let lod0_limit = results["models"][0]["lods"][0]["characters_per_draw"]
        .as_u64()
        .unwrap();
    assert!(
        single["measured"]
            .as_str()
            .unwrap()
            .contains(&lod0_limit.to_string()),
        "{single}"
    );
    for figure in section["figures"].as_array().unwrap() {
        let file = out_dir.join(figure["file"].as_str().unwrap());
        assert!(file.exists(), "{}", file.display());
    }
    // Every measured run is in the machine-readable results, with its stage times.
    let runs = section["results"]["table1"].as_array().unwrap();
    assert_eq!(runs.len(), 2 * 3 * 3);
    assert!(runs.iter().all(|r| r["fps"].as_f64().unwrap() > 0.0));
    assert!(runs
        .iter()
        .all(|r| r["passes"]["pass1_draws"].as_u64().is_some()));

    // Fig. 4-5 are run in the paper's setup: three meshes and culling, no sprites; LOD 2
    // reaches to the far plane.
    let paper_setup = results["lod_runs"].as_array().unwrap();
    let extension = results["sprite_runs"].as_array().unwrap();
    assert_eq!(paper_setup.len(), 4, "two figures x two methods");
    assert_eq!(extension.len(), 4);
    for (paper, ext) in paper_setup.iter().zip(extension) {
        assert_eq!(paper["sprites_enabled"], false);
        assert_eq!(paper["passes"]["sprites"], 0, "{paper}");
        assert!(paper["per_lod"][2].as_u64().unwrap() > 0);
        assert_eq!(ext["sprites_enabled"], true);
        // The same crowd, side by side: the extension only turns far LOD 2 characters
        // into sprites.
        assert_eq!(
            (&paper["model"], &paper["method"]),
            (&ext["model"], &ext["method"])
        );
        assert_eq!(paper["culled"], ext["culled"]);
        assert_eq!(paper["per_lod"][0], ext["per_lod"][0]);
        assert_eq!(paper["per_lod"][1], ext["per_lod"][1]);
        assert_eq!(
            paper["per_lod"][2].as_u64().unwrap(),
            ext["per_lod"][2].as_u64().unwrap() + ext["passes"]["sprites"].as_u64().unwrap()
        );
    }
    // The Fig. 3-5 table keeps the sprite runs in rows of their own, marked as an extension.
    let fig3_5 = section["tables"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["caption"].as_str().unwrap().starts_with("Fig. 3-5"))
        .unwrap();
    let figures: Vec<&str> = fig3_5["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r[0].as_str().unwrap())
        .collect();
    assert_eq!(
        figures,
        [
            "Fig. 4",
            "Fig. 5",
            "Fig. 4 + sprites (extension)",
            "Fig. 5 + sprites (extension)"
        ]
    );

    // The models' bone counts, the spear and the LOD distances are declared as this
    // project's choices, with the values the code uses.
    let fidelity = section["fidelity"].as_array().unwrap();
    let deviation = |feature: &str| {
        fidelity
            .iter()
            .find(|f| f["feature"].as_str().unwrap().starts_with(feature))
            .unwrap_or_else(|| panic!("no fidelity row '{feature}'"))["deviation"]
            .as_str()
            .unwrap()
            .to_string()
    };
    let models = deviation("Character models");
    for kind in ModelKind::ALL {
        let bones = CharacterModel::build(kind).unwrap().bone_count();
        assert!(
            models.contains(&format!("{bones} bones")),
            "{kind:?} {bones}: {models}"
        );
    }
    assert!(models.contains("spear") && models.contains("this project's choices"));
    let lod = deviation("3 LODs");
    let [near, middle] = LodPolicy::default().mesh_until;
    assert!(
        lod.contains(&format!(
            "{near:.0} m and {middle:.0} m, are this project's"
        )),
        "{lod}"
    );
    let sprites = deviation("Sprites");
    assert!(sprites.contains("extension, not in the paper"), "{sprites}");
    let one_draw = deviation("Skinning in a pixel shader");
    assert!(
        one_draw.starts_with("not one draw for all") && one_draw.contains(&lod0_limit.to_string()),
        "{one_draw}"
    );
    std::fs::remove_dir_all(&out_dir).ok();
}

#[test]
fn crowd_command_runs_the_papers_lod_setup_sprites_on_request_and_forced_batches() {
    let run = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec![
            "crowd",
            "--characters",
            "40",
            "--frames",
            "1",
            "--size",
            "96x64",
            "--json",
        ];
        args.extend_from_slice(extra);
        let out = classic_gpgpu(&args);
        assert!(
            out.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let lod = run(&["--lod"]);
    assert_eq!(lod["run"]["lod_and_culling"], true);
    assert_eq!(lod["run"]["sprites_enabled"], false);
    assert_eq!(lod["run"]["passes"]["sprites"], 0);
    let sprites = run(&["--lod", "--sprites"]);
    assert_eq!(sprites["run"]["sprites_enabled"], true);
    // 40 characters in pass-1 draws of 16: three draws instead of the one that fits.
    let batched = run(&["--skin-batch", "16"]);
    assert_eq!(batched["run"]["passes"]["pass1_draws"], 3);
    assert_eq!(batched["pass1_characters_per_draw"][0], 16);
    assert_eq!(run(&[])["run"]["passes"]["pass1_draws"], 1);
    for (args, needle) in [
        (vec!["crowd", "--sprites"], "--lod"),
        (vec!["crowd", "--skin-batch", "0"], "--skin-batch"),
    ] {
        let out = classic_gpgpu(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(
            err.contains(needle) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

/// A character placed with a transform the fp32 bone textures cannot hold (scaled by 10^39)
/// skins to infinities and NaN: reading the vertices back is an error naming the model,
/// the LOD and the pass, not numbers that poison whatever compares or draws them.
#[test]
fn skinned_vertices_that_are_not_finite_are_an_error() {
    let ctx = context();
    let model = CharacterModel::build(ModelKind::Soldier).unwrap();
    let mut renderer = CrowdRenderer::new(&ctx, model).unwrap();
    let (mut models, phases) = scattered(4);
    let ids = [0, 1, 2, 3];
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    assert!(renderer.skin_to_vbo(1, &instances, &ids).is_ok());
    models[2] *= DAffine3::from_scale(DVec3::splat(1e39));
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    let err = renderer
        .skin_to_vbo(1, &instances, &ids)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("crowd: the skinned vertices of 4 Soldier characters (batch 0) at LOD 1")
            && err.contains("pass 'crowd pass 1 (skinning)'"),
        "{err}"
    );
}
