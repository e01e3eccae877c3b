#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006):
// the normal of a bilinear patch, shared by the tracers and the normal pyramid's first pass.

uniform vec3 u_world_to_grid;  // a diagonal scale

// The world normal of a bilinear patch with corners h, `side` patches wide, at local (s, t).
vec3 patch_normal(vec4 h, vec2 st, float side) {
    float dhds = ((h.y - h.x) + (h.x - h.y - h.z + h.w) * st.y) / side;
    float dhdt = ((h.z - h.x) + (h.x - h.y - h.z + h.w) * st.x) / side;
    // World slopes: dz/dx = (dH/ds) (grid x per world x) / (grid z per world z).
    vec2 slope = vec2(dhds, dhdt) * u_world_to_grid.xy / u_world_to_grid.z;
    return normalize(vec3(-slope, 1.0));
}

// The direction toward the one directional light (world).
vec3 light_direction() {
    return normalize(vec3(0.4, 0.3, 0.85));
}
