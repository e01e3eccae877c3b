#version 430 core
// Lesson 7, the compute counterpart: no layers at all. One invocation per pixel casts the
// pixel's ray through every triangle and keeps the depths it meets, sorted: what the peels
// find one pass at a time, found in one pass (the way a CUDA-era code would do it).

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Corners { vec4 b_corners[]; }; // 3 per triangle, window x, y in pixels, depth
layout(std430, binding = 1) writeonly buffer Layers { float b_layers[]; };  // MAX_LAYERS per pixel, 2.0 where none
layout(std430, binding = 2) writeonly buffer Counts { uint b_counts[]; };   // hits per pixel

const int MAX_LAYERS = 8;
uniform uint u_triangles;
uniform ivec2 u_size;

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, uvec2(u_size)))) return;
    vec2 p = vec2(pixel) + 0.5; // the pixel centre, where the rasterizer samples
    float depths[MAX_LAYERS];
    for (int k = 0; k < MAX_LAYERS; ++k) depths[k] = 2.0;
    uint hits = 0u;
    for (uint t = 0u; t < u_triangles; ++t) {
        vec3 a = b_corners[3u * t].xyz, b = b_corners[3u * t + 1u].xyz, c = b_corners[3u * t + 2u].xyz;
        // Barycentric coordinates of the centre in the projected triangle.
        float area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if (area == 0.0) continue;
        float wa = ((b.x - p.x) * (c.y - p.y) - (c.x - p.x) * (b.y - p.y)) / area;
        float wb = ((c.x - p.x) * (a.y - p.y) - (a.x - p.x) * (c.y - p.y)) / area;
        float wc = 1.0 - wa - wb;
        if (wa < 0.0 || wb < 0.0 || wc < 0.0) continue;
        // A hit: insert its depth in order.
        float z = wa * a.z + wb * b.z + wc * c.z;
        hits += 1u;
        for (int k = 0; k < MAX_LAYERS; ++k) {
            if (z < depths[k]) {
                float moved = depths[k];
                depths[k] = z;
                z = moved;
            }
        }
    }
    uint i = pixel.y * uint(u_size.x) + pixel.x;
    b_counts[i] = hits;
    for (int k = 0; k < MAX_LAYERS; ++k) b_layers[i * uint(MAX_LAYERS) + uint(k)] = depths[k];
}
