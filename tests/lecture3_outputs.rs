//! What `classic-gpgpu lecture3 ...` writes and prints is what the GPU computed: the .npy files
//! of `random`, `displace` and `light` equal what the GPU reads back for the same input in this
//! process (or, for the random numbers, the CPU generator the GPU is bit-exact with), the
//! histogram's JSON counts are the GPU's (equal to the CPU's), the pyramid PNG holds the GPU's
//! three pyramids. Exact equality: the same renderer computes the same floats.

use classic_gpgpu::files::read_npy;
use classic_gpgpu::lecture3::displacement::{Camera, DisplacementRenderer, Method, Surface};
use classic_gpgpu::lecture3::height_map::{HeightMap, SHIPPED_SIZE};
use classic_gpgpu::lecture3::random_texture::HybridTaus;
use classic_gpgpu::report::lecture3 as bench;
use classic_gpgpu::timing::Runs;
use common::{classic_gpgpu, context, json_of};
use std::path::PathBuf;

mod common;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lecture3_outputs_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn stdout_of(args: &[&str]) -> String {
    let out = classic_gpgpu(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    String::from_utf8_lossy(&out.stdout).to_string()
}

#[test]
fn random_npy_holds_every_number_the_gpu_made() {
    let dir = scratch("random");
    let npy = dir.join("numbers.npy");
    let text = stdout_of(&[
        "lecture3",
        "random",
        "--size",
        "8",
        "--steps",
        "3",
        "--seed",
        "11",
        "--npy",
        npy.to_str().unwrap(),
    ]);
    assert!(text.contains(&format!("wrote {}", npy.display())), "{text}");
    let (shape, values) = read_npy(&npy).unwrap();
    assert_eq!(shape, vec![3, 8, 8]);
    let mut generators: Vec<HybridTaus> = (0..64).map(|i| HybridTaus::seeded(11, i)).collect();
    for step in 0..3 {
        for (i, g) in generators.iter_mut().enumerate() {
            assert_eq!(
                values[step * 64 + i].to_bits(),
                g.next_f32().to_bits(),
                "step {step}, generator {i}"
            );
        }
    }
    // An existing file is kept without --force.
    let out = classic_gpgpu(&[
        "lecture3",
        "random",
        "--size",
        "8",
        "--npy",
        npy.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--force"));
}

#[test]
fn random_with_one_generator_is_refused_instead_of_printing_nan() {
    let out = classic_gpgpu(&["lecture3", "random", "--size", "1", "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("--size"), "{stderr}");
    assert!(!String::from_utf8_lossy(&out.stdout).contains("NaN"));
}

#[test]
fn displace_npy_is_the_frame_the_gpu_drew() {
    let dir = scratch("displace");
    let out = dir.join("frame");
    let v = json_of(&[
        "lecture3",
        "displace",
        "--size",
        "24",
        "--elevation",
        "30",
        "--no-check",
        "--npy",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["written"].as_array().unwrap().len(), 3, "{v}");
    let ctx = context();
    let surface = Surface::new(HeightMap::generated(SHIPPED_SIZE), bench::DEPTH).unwrap();
    let renderer = DisplacementRenderer::new(&ctx, surface).unwrap();
    let camera = Camera::orbit(
        renderer.surface().centre(),
        bench::DISTANCE,
        225.0,
        30.0,
        24,
        24,
    );
    let target = renderer.target(24, 24).unwrap();
    renderer.render(&target, &camera, Method::Pyramid).unwrap();
    let frame = renderer.read(&target).unwrap();
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let (shape, hit) = read_npy(&out.join("hit.npy")).unwrap();
    assert_eq!(shape, vec![24, 24, 4]);
    assert_eq!(bits(&hit), bits(frame.hits()));
    let (shape, depth) = read_npy(&out.join("depth.npy")).unwrap();
    assert_eq!(shape, vec![24, 24]);
    assert_eq!(bits(&depth), bits(&frame.depth));
    let (shape, kind) = read_npy(&out.join("kind.npy")).unwrap();
    assert_eq!(shape, vec![24, 24]);
    assert_eq!(kind, frame.kinds());
    assert!(kind.contains(&1.0), "some pixels show the surface");
}

#[test]
fn light_npy_is_the_irradiance_the_gpu_gathered_and_each_file_is_named() {
    let dir = scratch("light");
    let out = dir.join("light");
    let png = dir.join("light.png");
    let text = stdout_of(&[
        "lecture3",
        "light",
        "--vpls",
        "8",
        "--size",
        "32",
        "--theta",
        "0.5",
        "--npy",
        out.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
    ]);
    let npy = out.join("irradiance.npy");
    for file in [&npy, &png] {
        assert!(
            text.contains(&format!("wrote {}", file.display())),
            "{text}"
        );
    }
    let ctx = context();
    let (_, lighting, ()) =
        bench::light_run(&ctx, 8, 32, 32, &[0.5], Runs::exactly(1), |_| Ok(())).unwrap();
    let gathered: Vec<f32> = lighting
        .gathers
        .read()
        .unwrap()
        .iter()
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let (shape, irradiance) = read_npy(&npy).unwrap();
    assert_eq!(shape, vec![32, 32, 3]);
    assert_eq!(irradiance, gathered);
    assert!(irradiance.iter().any(|&e| e > 0.0));
    // Under --json nothing but the JSON is printed.
    let v = json_of(&[
        "lecture3",
        "light",
        "--vpls",
        "8",
        "--size",
        "32",
        "--npy",
        dir.join("again").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["written"].as_array().unwrap().len(), 1);
}

#[test]
fn histogram_json_counts_are_the_gpus_and_images_are_not_called_height_maps() {
    let v = json_of(&[
        "lecture3",
        "histogram",
        "--values",
        "5000",
        "--bins",
        "32",
        "--json",
    ]);
    let counts: Vec<f64> = v["counts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap())
        .collect();
    assert_eq!(counts.len(), 32);
    let skewed = bench::skewed_values(5000, 3);
    let bins = classic_gpgpu::lecture3::blend_histogram::Bins::new(0.0, 1.0, 32, 16384).unwrap();
    let (cpu, _) = classic_gpgpu::lecture3::blend_histogram::cpu_histogram(&skewed, None, &bins);
    assert_eq!(counts, cpu);
    let dir = scratch("histogram");
    let not_png = dir.join("notes.png");
    std::fs::write(&not_png, "not an image").unwrap();
    let out = classic_gpgpu(&[
        "lecture3",
        "histogram",
        "--image",
        not_png.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("image") && !stderr.contains("height map"),
        "{stderr}"
    );
}

#[test]
fn pyramid_png_shows_the_three_gpu_pyramids() {
    let dir = scratch("pyramid");
    let png = dir.join("pyramid.png");
    stdout_of(&["lecture3", "pyramid", "--png", png.to_str().unwrap()]);
    let picture = image::open(&png).unwrap();
    // Three atlases of the 64x64 map (64 + 32 wide each), each a titled panel with its
    // colour key, at a whole number of pixels per texel: wider and taller than the atlases.
    assert!(
        picture.width() >= 3 * 96 && picture.height() > 64,
        "{}x{}",
        picture.width(),
        picture.height()
    );
}
