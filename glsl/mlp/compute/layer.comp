#version 430 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 2 and 3 in one compute pass (then and
// now).
// One layer R = activation(X W' + B) as a tiled matrix product in shared memory: each
// 16 x 16 work group computes a 16 x 16 block of R (16 input vectors by 16 output nodes).
// Stepping along the N inputs 16 at a time, the group loads one tile of X and one of W into
// shared memory, each invocation loading one value of each, and every invocation then sums
// its 16 products from there. Bias and activation are applied in the same pass.

layout(local_size_x = 16, local_size_y = 16) in;

// Row-major: X is L x N (row j is input vector j), W is M x N (row i: weights into node i),
// R is L x M, the next layer's X.
layout(std430, binding = 0) readonly buffer Inputs { float b_x[]; };
layout(std430, binding = 1) readonly buffer Weights { float b_w[]; };
layout(std430, binding = 2) readonly buffer Bias { float b_bias[]; };
layout(std430, binding = 3) writeonly buffer Result { float b_r[]; };

uniform uint u_l;        // input vectors
uniform uint u_n;        // inputs per vector
uniform uint u_m;        // output nodes
uniform bool u_sigmoid;  // eq. 3's sigmoid, or identity

shared float s_x[16][16];
shared float s_w[16][16];

void main() {
    uint lx = gl_LocalInvocationID.x;
    uint ly = gl_LocalInvocationID.y;
    uint vector = gl_WorkGroupID.y * 16u + ly;  // row of X and R
    uint node = gl_WorkGroupID.x * 16u + lx;    // column of R
    uint w_row = gl_WorkGroupID.x * 16u + ly;   // the W row this invocation loads
    float sum = 0.0;
    for (uint k0 = 0u; k0 < u_n; k0 += 16u) {
        uint k = k0 + lx;
        s_x[ly][lx] = (vector < u_l && k < u_n) ? b_x[vector * u_n + k] : 0.0;
        s_w[ly][lx] = (w_row < u_m && k < u_n) ? b_w[w_row * u_n + k] : 0.0;
        barrier();
        for (uint t = 0u; t < 16u; t++) {
            sum += s_x[ly][t] * s_w[lx][t];
        }
        barrier();
    }
    if (vector < u_l && node < u_m) {
        float m = sum + b_bias[node];
        b_r[vector * u_m + node] = u_sigmoid ? 1.0 / (1.0 + exp(-m)) : m;
    }
}
