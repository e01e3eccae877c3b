//! CPU side of paper 2: characters, LODs, skinning reference, validation, culling, steering.

use std::collections::HashMap;

use classic_gpgpu::crowd::body_part::Tessellation;
use classic_gpgpu::crowd::culling::{plan_frame, Camera, Frustum};
use classic_gpgpu::crowd::lod::tessellate_to_budget;
use classic_gpgpu::crowd::steering::Crowd;
use classic_gpgpu::crowd::{
    cpu_skinning, horse, soldier, CharacterModel, Level, LodPolicy, ModelKind, SkinError,
    SkinnedMesh, LOD_TRIANGLES,
};
use glam::{DAffine3, DQuat, DVec3, Vec3};

fn models() -> Vec<CharacterModel> {
    ModelKind::ALL
        .iter()
        .map(|&k| CharacterModel::build(k).expect("model builds"))
        .collect()
}

#[test]
fn lods_have_the_papers_polygon_counts() {
    for model in models() {
        let counts: Vec<usize> = model.lods.iter().map(SkinnedMesh::triangle_count).collect();
        assert_eq!(counts, LOD_TRIANGLES, "{:?}", model.kind);
        // Coarser levels also have fewer vertices (pass 1 work scales with m).
        let m: Vec<usize> = model.lods.iter().map(SkinnedMesh::vertex_count).collect();
        assert!(
            m[0] > m[1] && m[1] > m[2],
            "{:?} vertex counts {m:?}",
            model.kind
        );
        eprintln!("{:?}: vertices per LOD {m:?}", model.kind);
    }
}

#[test]
fn budget_solver_hits_other_targets_and_rejects_impossible_ones() {
    let parts = soldier::blueprint().parts;
    for target in [200, 312, 400, 544, 1000, 1084, 2000, 5000] {
        let tess = tessellate_to_budget(&parts, target).unwrap();
        let total: usize = tess.iter().map(Tessellation::triangle_count).sum();
        assert_eq!(total, target);
        assert!(tess
            .iter()
            .all(|t| t.segments >= 4 && t.segments % 2 == 0 && t.rings >= 2));
    }
    assert!(
        tessellate_to_budget(&parts, 1083).is_err(),
        "odd totals are impossible"
    );
    let err = tessellate_to_budget(&parts, 10).unwrap_err();
    assert!(err.to_string().contains("exactly 10 triangles"), "{err}");
}

/// Every edge is used by exactly two triangles, once in each direction: the surface is
/// closed and consistently oriented.
fn assert_closed_and_oriented(mesh: &SkinnedMesh, what: &str) {
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for t in &mesh.mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *edges.entry((a, b)).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &edges {
        assert_eq!(count, 1, "{what}: edge {a}->{b} used {count} times");
        assert_eq!(
            edges.get(&(b, a)),
            Some(&1),
            "{what}: edge {a}->{b} has no twin"
        );
    }
}

fn signed_volume(mesh: &SkinnedMesh) -> f64 {
    mesh.mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.mesh.positions[i as usize].as_dvec3());
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

#[test]
fn meshes_are_closed_outward_and_plausibly_sized() {
    for model in models() {
        for (lod, mesh) in model.lods.iter().enumerate() {
            let what = format!("{:?} LOD {lod}", model.kind);
            assert_closed_and_oriented(mesh, &what);
            // Outward winding gives positive volume; a person is ~0.07 m^3, a horse ~0.5.
            let volume = signed_volume(mesh);
            let expected = match model.kind {
                ModelKind::Soldier => 0.03..0.15,
                ModelKind::Horse => 0.2..1.0,
            };
            assert!(expected.contains(&volume), "{what}: volume {volume}");
            // Normals point away from the part they belong to: on average along the
            // direction from the mesh centroid for a closed shell of convex parts.
            assert!(
                mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4),
                "{what}"
            );
        }
    }
}

#[test]
fn weights_are_smooth_sparse_and_valid() {
    for model in models() {
        let mesh = &model.lods[0];
        mesh.validate(model.bone_count()).unwrap();
        let blended = mesh
            .bone_weights
            .iter()
            .filter(|w| w.iter().filter(|&&x| x > 0.0).count() > 1)
            .count();
        // Joints blend: a good share of vertices has more than one influence.
        assert!(
            blended * 5 > mesh.vertex_count(),
            "{:?}: {blended} blended",
            model.kind
        );
        // Every bone but the root moves some vertex (no dead bones in the rig).
        let mut used = vec![false; model.bone_count()];
        for (ix, w) in mesh.bone_indices.iter().zip(&mesh.bone_weights) {
            for k in 0..4 {
                if w[k] > 0.0 {
                    used[ix[k] as usize] = true;
                }
            }
        }
        assert!(
            used.iter().all(|&u| u),
            "{:?}: unused bones {used:?}",
            model.kind
        );
    }
}

#[test]
fn bad_weights_and_bone_indices_are_rejected_with_clear_errors() {
    let model = CharacterModel::build(ModelKind::Soldier).unwrap();
    let bones = model.bone_count();
    let mut mesh = model.lods[2].clone();
    mesh.bone_weights[7] = [0.5, 0.3, 0.1, 0.0];
    let err = mesh.validate(bones).unwrap_err();
    assert!(
        matches!(err, SkinError::WeightSum { vertex: 7, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("vertex 7") && err.to_string().contains("sum to 0.9"));

    let mut mesh = model.lods[2].clone();
    mesh.bone_indices[11][2] = bones as u32;
    let err = mesh.validate(bones).unwrap_err();
    assert_eq!(
        err,
        SkinError::BoneIndex {
            vertex: 11,
            slot: 2,
            index: bones as u32,
            bones
        }
    );
    assert!(err.to_string().contains("out of range"), "{err}");

    let mut mesh = model.lods[2].clone();
    mesh.bone_weights[3] = [1.5, -0.5, 0.0, 0.0];
    assert!(matches!(
        mesh.validate(bones),
        Err(SkinError::BadWeight {
            vertex: 3,
            slot: 1,
            ..
        })
    ));

    let mut mesh = model.lods[2].clone();
    mesh.bone_weights.pop();
    assert!(matches!(
        mesh.validate(bones),
        Err(SkinError::LengthMismatch { .. })
    ));

    // The constructor validates too.
    let m = model.lods[2].clone();
    let mut weights = m.bone_weights.clone();
    weights[0] = [f32::NAN, 0.0, 0.0, 0.0];
    assert!(SkinnedMesh::new(m.mesh, m.normals, m.bone_indices, weights, bones).is_err());
}

#[test]
fn bind_pose_skinning_is_the_identity_and_rigid_motion_is_exact() {
    let model = CharacterModel::build(ModelKind::Horse).unwrap();
    let mesh = &model.lods[1];
    let bind = model
        .skeleton
        .skinning_matrices(&model.skeleton.bind_pose(), DAffine3::IDENTITY);
    let skinned = cpu_skinning::skin(mesh, &bind);
    // Weights are f32 and sum to one only to a few ulp (2^-24 each): positions within
    // 3 m of the origin are reproduced to 1e-6.
    for (p, q) in skinned.positions.iter().zip(&mesh.mesh.positions) {
        assert!(p.distance(q.as_dvec3()) < 1e-6);
    }
    // A whole-character placement moves every vertex rigidly.
    let place = DAffine3::from_rotation_translation(
        DQuat::from_rotation_y(0.7),
        DVec3::new(3.0, 0.0, -2.0),
    );
    let moved = cpu_skinning::skin(
        mesh,
        &model
            .skeleton
            .skinning_matrices(&model.skeleton.bind_pose(), place),
    );
    for (p, q) in moved.positions.iter().zip(&mesh.mesh.positions) {
        assert!(p.distance(place.transform_point3(q.as_dvec3())) < 1e-6);
    }
}

#[test]
fn lbs_matches_a_hand_computed_blend() {
    // Two bones, one vertex halfway between: rotating the child by 90 degrees about z
    // about its head at (0,1,0) moves a fully child-weighted point (0,2,0) to (-1,1,0),
    // and a 50/50 point to the average of both bones' images.
    use classic_gpgpu::crowd::skeleton::{Bone, Skeleton};
    let skeleton = Skeleton::new(vec![
        Bone {
            name: "a",
            parent: None,
            head: DVec3::ZERO,
            tail: DVec3::Y,
        },
        Bone {
            name: "b",
            parent: Some(0),
            head: DVec3::Y,
            tail: DVec3::Y * 2.0,
        },
    ])
    .unwrap();
    let mut pose = skeleton.bind_pose();
    pose.local_rotations[1] = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
    let bones = skeleton.skinning_matrices(&pose, DAffine3::IDENTITY);
    let mesh = SkinnedMesh::new(
        classic_gpgpu::mesh::Mesh::new(
            vec![Vec3::new(0.0, 2.0, 0.0), Vec3::new(0.0, 2.0, 0.0)],
            vec![],
        ),
        vec![Vec3::X, Vec3::X],
        vec![[1, 0, 0, 0], [0, 1, 0, 0]],
        vec![[1.0, 0.0, 0.0, 0.0], [0.5, 0.5, 0.0, 0.0]],
        2,
    )
    .unwrap();
    let out = cpu_skinning::skin(&mesh, &bones);
    assert!(out.positions[0].distance(DVec3::new(-1.0, 1.0, 0.0)) < 1e-12);
    assert!(out.positions[1].distance(DVec3::new(-0.5, 1.5, 0.0)) < 1e-12);
    assert!(out.normals[0].distance(DVec3::Y) < 1e-12);
    // Skeletons with a misplaced parent are refused.
    assert!(Skeleton::new(vec![Bone {
        name: "x",
        parent: Some(0),
        head: DVec3::ZERO,
        tail: DVec3::Y
    }])
    .is_err());
}

#[test]
fn animation_loops_moves_limbs_and_stays_inside_the_bound() {
    for model in models() {
        let mesh = &model.lods[2];
        let at = |phase: f64| {
            let pose = model.clip.sample(&model.skeleton, phase);
            cpu_skinning::skin(
                mesh,
                &model.skeleton.skinning_matrices(&pose, DAffine3::IDENTITY),
            )
        };
        let (a, b, c) = (at(0.3), at(1.3), at(0.8));
        let max_diff = |x: &[DVec3], y: &[DVec3]| {
            x.iter()
                .zip(y)
                .map(|(p, q)| p.distance(*q))
                .fold(0.0, f64::max)
        };
        assert!(
            max_diff(&a.positions, &b.positions) < 1e-9,
            "clip loops with period 1"
        );
        assert!(
            max_diff(&a.positions, &c.positions) > 0.1,
            "limbs move half a cycle apart"
        );
        for k in 0..20 {
            for p in at(k as f64 / 20.0 + 0.013).positions {
                assert!(p.as_vec3().distance(model.bound_centre) <= model.bound_radius);
            }
        }
    }
}

#[test]
fn blueprints_name_their_bones() {
    let s = soldier::blueprint().skeleton;
    let h = horse::blueprint().skeleton;
    assert!(s.index_of("hand_r").is_some() && s.index_of("spear").is_some());
    assert_eq!(h.len(), 20);
}

fn camera() -> Camera {
    Camera {
        eye: Vec3::new(0.0, 2.0, 0.0),
        target: Vec3::new(0.0, 2.0, 10.0),
        fov_y: 60f32.to_radians(),
        aspect: 1.0,
        near: 0.1,
        far: 200.0,
    }
}

#[test]
fn frustum_keeps_what_is_in_view_and_drops_what_is_not() {
    let f = Frustum::from_view_projection(camera().view_projection());
    assert!(f.intersects_sphere(Vec3::new(0.0, 2.0, 10.0), 0.5));
    assert!(
        !f.intersects_sphere(Vec3::new(0.0, 2.0, -10.0), 0.5),
        "behind the eye"
    );
    assert!(
        !f.intersects_sphere(Vec3::new(0.0, 2.0, 300.0), 0.5),
        "beyond the far plane"
    );
    // The half-width of the view at depth 10 is tan(30 deg) * 10 = 5.77.
    assert!(!f.intersects_sphere(Vec3::new(-7.0, 2.0, 10.0), 1.0));
    assert!(
        f.intersects_sphere(Vec3::new(-6.5, 2.0, 10.0), 1.0),
        "sphere straddles the edge"
    );
}

#[test]
fn hand_placed_characters_get_the_right_level_or_are_culled() {
    let model = CharacterModel::build(ModelKind::Soldier).unwrap();
    let at = |x: f64, z: f64| DAffine3::from_translation(DVec3::new(x, 0.0, z));
    let placed = [
        at(0.0, 5.0),   // near: LOD 0
        at(1.0, 30.0),  // LOD 1
        at(-3.0, 60.0), // LOD 2
        at(0.0, 150.0), // LOD 2 in the paper's setup, a sprite with the extension
        at(0.0, -5.0),  // behind: culled
        at(80.0, 10.0), // far right: culled
        at(0.0, 250.0), // beyond far plane: culled
    ];
    let policy = LodPolicy::default();
    let plan = plan_frame(
        &placed,
        model.bound_centre,
        model.bound_radius,
        &camera(),
        Some(&policy),
        true,
    );
    // The paper's setup has no sprite level: the far character is LOD 2.
    assert_eq!(plan.lods, [vec![0], vec![1], vec![2, 3]]);
    assert!(plan.sprites.is_empty());
    assert_eq!(plan.culled, 3);
    assert_eq!(plan.skinned(), 4);
    let with_sprites = LodPolicy::with_sprites();
    let extended = plan_frame(
        &placed,
        model.bound_centre,
        model.bound_radius,
        &camera(),
        Some(&with_sprites),
        true,
    );
    assert_eq!(extended.lods, [vec![0], vec![1], vec![2]]);
    assert_eq!(extended.sprites, vec![3]);
    assert_eq!(extended.culled, 3);
    // Without culling or LOD (the paper's Table 1 setting) every character is LOD 0.
    let all = plan_frame(
        &placed,
        model.bound_centre,
        model.bound_radius,
        &camera(),
        None,
        false,
    );
    assert_eq!(all.lods[0], (0..placed.len()).collect::<Vec<_>>());
    assert_eq!(policy.select(15.0), Level::Mesh(0));
    assert_eq!(policy.select(15.01), Level::Mesh(1));
    assert_eq!(policy.select(1000.0), Level::Mesh(2));
    assert_eq!(with_sprites.select(15.01), Level::Mesh(1));
    assert_eq!(with_sprites.select(1000.0), Level::Sprite);
}

#[test]
fn steering_keeps_characters_apart_and_inside_and_advances_phases() {
    let squeezed = |separation_weight: f32| {
        let mut crowd = Crowd::new(60, 2.0, 1.4, 7);
        crowd.params.separation_weight = separation_weight;
        // Everyone starts in a small patch, so separation has work to do.
        for (i, a) in crowd.agents.iter_mut().enumerate() {
            a.position = glam::Vec2::new((i % 8) as f32 * 0.3, (i / 8) as f32 * 0.3);
        }
        crowd
    };
    let mut crowd = squeezed(Crowd::new(1, 2.0, 1.4, 7).params.separation_weight);
    let mut control = squeezed(0.0);
    let start_phase: Vec<f64> = crowd.agents.iter().map(|a| a.phase).collect();
    let (mut worst, mut worst_control) = (f32::INFINITY, f32::INFINITY);
    for step in 0..300 {
        crowd.step(1.0 / 30.0, 1.4);
        control.step(1.0 / 30.0, 1.4);
        if step >= 150 {
            worst = worst.min(crowd.min_separation());
            worst_control = worst_control.min(control.min_separation());
        }
    }
    // Once spread out, steered characters stay well apart; without the separation term
    // they bump into each other.
    assert!(
        worst > 0.5 && worst > 2.0 * worst_control,
        "steered {worst}, control {worst_control}"
    );
    let (lo, hi) = crowd.params.bounds;
    assert!(crowd
        .agents
        .iter()
        .all(|a| a.position.cmpge(lo).all() && a.position.cmple(hi).all()));
    // Each character walked and its animation advanced by its own amount.
    let advanced: Vec<f64> = crowd
        .agents
        .iter()
        .zip(&start_phase)
        .map(|(a, s)| a.phase - s)
        .collect();
    assert!(advanced.iter().all(|&d| d > 0.5), "{advanced:?}");
    let spread = advanced.iter().cloned().fold(f64::MIN, f64::max)
        - advanced.iter().cloned().fold(f64::MAX, f64::min);
    assert!(spread > 0.1, "phases advance independently");
    // Deterministic for a seed.
    let mut again = Crowd::new(60, 2.0, 1.4, 7);
    let mut first = Crowd::new(60, 2.0, 1.4, 7);
    again.step(0.1, 1.4);
    first.step(0.1, 1.4);
    assert_eq!(again.agents, first.agents);
}

#[test]
fn models_and_methods_parse_from_their_names_and_refuse_others() {
    use classic_gpgpu::crowd::Method;
    for kind in ModelKind::ALL {
        assert_eq!(kind.to_string().parse::<ModelKind>(), Ok(kind));
    }
    for method in Method::ALL {
        assert_eq!(method.to_string().parse::<Method>(), Ok(method));
    }
    let e = "dragon".parse::<ModelKind>().unwrap_err();
    assert!(e.contains("dragon") && e.contains("soldier"), "{e}");
    let e = "one-pass".parse::<Method>().unwrap_err();
    assert!(e.contains("one-pass") && e.contains("two-pass"), "{e}");
}

#[test]
fn one_pass1_draw_holds_3712_characters_at_lod0_on_16384_texel_targets() {
    use classic_gpgpu::crowd::pass1_skinning::{characters_per_target, MAX_ROW_CHARACTERS};
    // The figure the module docs and the report give: 128 characters a row, floor(16384 /
    // m) blocks of m rows, for the soldier's and the horse's LOD 0 meshes.
    for model in models() {
        let m = model.lods[0].vertex_count() as u32;
        assert_eq!(
            characters_per_target(16384, m),
            3712,
            "{:?}, m = {m}",
            model.kind
        );
        assert_eq!(
            characters_per_target(16384, m),
            MAX_ROW_CHARACTERS * (16384 / m)
        );
    }
    // The target's side bounds it too: one row of bone texels per character.
    assert_eq!(characters_per_target(256, 1), 256);
    assert_eq!(characters_per_target(4096, 5000), 0);
}

#[test]
fn copies_of_one_crowd_stepped_once_per_round_equal_crowds_stepped_alone() {
    // Side-by-side runs step a crowd once per round and copy it into the scenes whose crowd
    // was equal to it: each scene must end as if it had stepped its own crowd.
    use classic_gpgpu::crowd::scene::{crowd_sources, lod_scene, step_crowd, table1_scene};
    let kind = ModelKind::Soldier;
    let stride = CharacterModel::build(kind).unwrap().clip.stride;
    let mut scenes = [
        table1_scene(kind, 40, 1.5, 1),
        lod_scene(kind, 40, 1.5, 2, LodPolicy::default()),
        table1_scene(kind, 40, 1.5, 1),
        lod_scene(kind, 40, 1.5, 2, LodPolicy::with_sprites()),
    ];
    let sources = crowd_sources(&scenes);
    assert_eq!(sources, [None, None, Some(0), Some(1)]);
    let mut alone: Vec<Crowd> = scenes.iter().map(|s| s.crowd.clone()).collect();
    for _ in 0..12 {
        for (i, crowd) in alone.iter_mut().enumerate() {
            step_crowd(&mut scenes, &sources, i, 1.0 / 30.0, stride);
            crowd.step(1.0 / 30.0, stride);
        }
    }
    for (i, (scene, crowd)) in scenes.iter().zip(&alone).enumerate() {
        assert!(scene.crowd == *crowd, "scene {i}");
    }
    assert!(
        scenes[0].crowd != scenes[1].crowd,
        "different seeds walk differently"
    );
}
