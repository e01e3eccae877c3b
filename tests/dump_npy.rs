//! `--dump` writes each float buffer as `.npy` beside its PNG: the exact values the GPU holds,
//! rows from GL's bottom, shape [height, width, channels].

use classic_gpgpu::collide::pipeline::{Options, StreamingCollider};
use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
use classic_gpgpu::collide::snapshot::{dump_buffers, dumped_textures};
use classic_gpgpu::collide::Predicate;
use classic_gpgpu::files::read_npy;
use classic_gpgpu::gl::npy::texture_floats;
use common::{context, json_of, soup};

mod common;

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("dump-npy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn bits(values: &[f32]) -> Vec<u32> {
    values.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn collide_dump_npy_equals_each_buffer_read_back() {
    let ctx = context();
    let (x, y) = (soup(120, 0.2, 3), soup(90, 0.2, 4));
    let options = Options {
        leaf_size: 4,
        readback: ReadbackMode::Hierarchical,
        predicate: Predicate::Moller,
        max_tile: None,
    };
    let mut collider = StreamingCollider::new(&ctx, &x, &y, options).unwrap();
    let frame = collider.frame(&x.positions, &y.positions).unwrap();
    assert_eq!(frame.tiles, 1, "the test reads P0 as one tile");
    assert!(frame.caps > 0, "the test needs colliding AABB pairs");
    let dir = scratch("collide");
    dump_buffers(&collider, &dir).unwrap();
    let textures = dumped_textures(&collider);
    assert!(
        textures.len() >= 6,
        "P0..P3, P1' and one stream segment each"
    );
    for (name, texture) in textures {
        assert!(dir.join(format!("{name}.png")).is_file(), "{name}.png");
        let (shape, values) = read_npy(&dir.join(format!("{name}.npy"))).unwrap();
        let (want_shape, want) = texture_floats(texture).unwrap().expect("a float texture");
        assert_eq!(shape, want_shape, "{name}");
        assert_eq!(
            shape,
            [
                texture.height() as usize,
                texture.width() as usize,
                texture.format().components()
            ],
            "{name}"
        );
        assert_eq!(bits(&values), bits(&want), "{name}: values differ");
    }
    // P0 marks each colliding AABB pair with a non-zero texel: the array counts the CAPs.
    let (_, p0) = read_npy(&dir.join("P0.npy")).unwrap();
    assert_eq!(p0.iter().filter(|&&v| v != 0.0).count(), frame.caps);
}

#[test]
fn mass_dump_writes_an_npy_beside_each_peel_png() {
    let dir = scratch("mass");
    let v = json_of(&[
        "mass",
        "torus",
        "--resolution",
        "16",
        "--dump",
        dir.to_str().unwrap(),
        "--json",
    ]);
    let peels = v["peels"].as_u64().unwrap();
    assert!(peels >= 2);
    let mut covered = 0;
    for k in 1..=peels {
        for t in 0..3 {
            let (shape, values) = read_npy(&dir.join(format!("peel{k}_target{t}.npy"))).unwrap();
            assert_eq!(shape, [16, 16, 4], "peel {k} target {t}");
            assert!(values.iter().all(|v| v.is_finite()), "peel {k} target {t}");
            covered += values.iter().filter(|&&v| v != 0.0).count();
        }
    }
    assert!(covered > 0, "every peel's integrands are zero");
}
