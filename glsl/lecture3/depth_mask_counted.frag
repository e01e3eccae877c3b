#version 420 core
// Lecture 3, debugging tip "remove `if` with the depth buffer": the masked pass counting its own
// runs (the prelude: version, early depth test, the counter).
// The depth-masked expensive shader, counting its own runs with an atomic counter (OpenGL
// 4.2), for contexts without pipeline statistics queries. A shader with a side effect may not
// have its depth test moved before it silently, so the early test the masked pass relies on is
// asked for explicitly; the counter then says how many pixels the shader ran on, which the
// occlusion query (samples that passed the test) cannot. (Fragment stage: this file, then
// depth_mask_common.glsl, then depth_mask_counted_main.frag.)

layout(early_fragment_tests) in;
layout(binding = 0, offset = 0) uniform atomic_uint u_runs;
