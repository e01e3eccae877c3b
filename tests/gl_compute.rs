//! The compute layer (OpenGL 4.3) on a real headless context: compute programs, storage
//! buffers, atomic counters and the shared-memory reduction, each against the CPU; on a
//! context below 4.3 (softpipe) the clear error, and the classic reduction still running.

use classic_gpgpu::gl::reduce::{ReduceOp, Reducer};
use classic_gpgpu::gl::reduce_shared::{passes_for, SharedReducer};
use classic_gpgpu::gl::{
    memory_barrier, AtomicCounters, Barrier, Buffer, BufferUsage, ComputeProgram, Texture,
    TextureFormat,
};
use classic_gpgpu::shader;
use common::compute_context;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

fn cpu_reduce(values: &[[f32; 4]], op: ReduceOp) -> [f64; 4] {
    let mut out = match op {
        ReduceOp::Min => [f64::INFINITY; 4],
        ReduceOp::Max | ReduceOp::Or => [f64::NEG_INFINITY; 4],
        _ => [0.0; 4],
    };
    for v in values {
        for c in 0..4 {
            let x = v[c] as f64;
            out[c] = match op {
                ReduceOp::Sum => out[c] + x,
                ReduceOp::Min => out[c].min(x),
                ReduceOp::Max => out[c].max(x),
                ReduceOp::CountNonZero => out[c] + (x != 0.0) as u8 as f64,
                ReduceOp::Or => out[c].max((x != 0.0) as u8 as f64),
            };
        }
    }
    out
}

fn random_values(n: usize, seed: u64) -> Vec<[f32; 4]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let zero = rng.gen_bool(0.3);
            [
                rng.gen_range(-1.0..1.0),
                rng.gen_range(0.0..1.0),
                if zero { 0.0 } else { 1.0 },
                rng.gen_range(-100.0..100.0),
            ]
        })
        .collect()
}

#[test]
fn below_4_3_compute_is_a_clear_error_and_the_classic_reduction_runs() {
    let (ctx, compute) = compute_context();
    let values = random_values(300, 1);
    // The classic ping-pong reduction runs on every context (20 x 15 texels).
    let flat: Vec<f32> = values.iter().flatten().copied().collect();
    let texture = Texture::from_f32(&ctx, 20, 15, TextureFormat::Rgba32F, &flat).unwrap();
    let classic = Reducer::new(&ctx, 20, 15)
        .unwrap()
        .reduce(&texture, ReduceOp::Max)
        .unwrap();
    let cpu = cpu_reduce(&values, ReduceOp::Max);
    for c in 0..4 {
        assert_eq!(classic[c] as f64, cpu[c]);
    }
    let made = SharedReducer::new(&ctx);
    if compute {
        assert!(made.is_ok());
    } else {
        let err = made.err().unwrap().to_string();
        assert!(err.contains("glsl/gl/compute/reduce.comp"), "{err}");
        assert!(err.contains("needs OpenGL 4.3"), "{err}");
        let err = AtomicCounters::new(&ctx, 1).err().unwrap().to_string();
        assert!(err.contains("atomic counters needs OpenGL 4.3"), "{err}");
    }
}

#[test]
fn shared_memory_reduction_matches_the_cpu_and_the_ping_pong_reduction() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let reducer = SharedReducer::new(&ctx).unwrap();
    for (n, seed) in [
        (1usize, 2u64),
        (2, 3),
        (511, 4),
        (512, 5),
        (513, 6),
        (70_000, 7),
    ] {
        let values = random_values(n, seed);
        let buffer = Buffer::from_slice(&ctx, &values, BufferUsage::Static).unwrap();
        for op in [
            ReduceOp::Sum,
            ReduceOp::Min,
            ReduceOp::Max,
            ReduceOp::CountNonZero,
            ReduceOp::Or,
        ] {
            let gpu = reducer.reduce(&buffer, n as u32, op).unwrap();
            let cpu = cpu_reduce(&values, op);
            for c in 0..4 {
                // fp32 sums of n terms of magnitude <= 100: error <= n * 2^-23 * sum |x|.
                let bound = match op {
                    ReduceOp::Sum => n as f64 * 1.2e-7 * 100.0 * n as f64 + 1e-6,
                    _ => 0.0,
                };
                assert!(
                    (gpu[c] as f64 - cpu[c]).abs() <= bound,
                    "n {n} {op:?} component {c}: GPU {} CPU {}",
                    gpu[c],
                    cpu[c]
                );
            }
        }
        // Beside the ping-pong reduction on the same values, laid out as a texture.
        let width = n.min(256);
        let height = n.div_ceil(width);
        let mut flat: Vec<f32> = values.iter().flatten().copied().collect();
        flat.resize(width * height * 4, 0.0);
        let texture = Texture::from_f32(
            &ctx,
            width as u32,
            height as u32,
            TextureFormat::Rgba32F,
            &flat,
        )
        .unwrap();
        let classic = Reducer::new(&ctx, width as u32, height as u32)
            .unwrap()
            .reduce(&texture, ReduceOp::Max)
            .unwrap();
        let shared = reducer.reduce(&buffer, n as u32, ReduceOp::Max).unwrap();
        assert_eq!(classic, shared, "n {n}: max, ping-pong vs shared memory");
    }
    assert_eq!(passes_for(1), 1);
    assert_eq!(passes_for(512), 1);
    assert_eq!(passes_for(513), 2);
    assert_eq!(passes_for(512 * 512 + 1), 3);
}

#[test]
fn segments_reduce_separately() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let (segments, n) = (5u32, 1500u32);
    let values = random_values((segments * n) as usize, 8);
    let buffer = Buffer::from_slice(&ctx, &values, BufferUsage::Static).unwrap();
    let reducer = SharedReducer::new(&ctx).unwrap();
    let gpu = reducer
        .reduce_segments(&buffer, segments, n, ReduceOp::Min)
        .unwrap();
    for (s, got) in gpu.iter().enumerate() {
        let part = &values[s * n as usize..(s + 1) * n as usize];
        let cpu = cpu_reduce(part, ReduceOp::Min);
        for c in 0..4 {
            assert_eq!(got[c] as f64, cpu[c], "segment {s} component {c}");
        }
    }
    let err = reducer
        .reduce_segments(&buffer, segments + 1, n, ReduceOp::Min)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("needs"), "{err}");
}

#[test]
fn atomic_counter_compacts_a_stream() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let program = ComputeProgram::new(&ctx, &[shader!("glsl/test/compact.comp")]).unwrap();
    assert_eq!(program.local_size(), [64, 1, 1]);
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let values: Vec<u32> = (0..1000).map(|_| rng.gen_range(0..100)).collect();
    let input = Buffer::from_slice(&ctx, &values, BufferUsage::Static).unwrap();
    let kept = Buffer::new(&ctx, values.len() * 4, BufferUsage::GpuCopy).unwrap();
    let counter = AtomicCounters::new(&ctx, 1).unwrap();
    for divisor in [3u32, 7] {
        counter.reset().unwrap();
        program
            .dispatch("compaction")
            .storage(0, &input)
            .storage(1, &kept)
            .counters(0, counter.buffer())
            .uniform("u_count", values.len() as u32)
            .uniform("u_divisor", divisor)
            .run_over(values.len() as u32)
            .unwrap();
        memory_barrier(&ctx, &[Barrier::BufferUpdate, Barrier::AtomicCounter]);
        let count = counter.read().unwrap()[0] as usize;
        let mut got: Vec<u32> = kept.read_prefix(count).unwrap();
        got.sort();
        let want: Vec<u32> = (0..values.len() as u32)
            .filter(|&i| values[i as usize].is_multiple_of(divisor))
            .collect();
        assert_eq!(got, want, "divisor {divisor}");
    }
    // A uniform the shader does not declare is an error naming it.
    let err = program
        .dispatch("compaction")
        .uniform("u_missing", 1u32)
        .run([1, 1, 1])
        .unwrap_err()
        .to_string();
    assert!(err.contains("u_missing"), "{err}");
}
