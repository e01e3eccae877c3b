#version 430 core
// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 2.1 "Computing mass properties with volume
// integrals", per triangle as a compute pass (then and now).
// The divergence-theorem sum written directly: one invocation per triangle (a, b, c) adds the
// signed tetrahedron (origin, a, b, c), whose integrals of 1, x, y, z, x², y², z², xy, yz, zx
// have closed forms. The sum over a closed surface is the solid's integrals, whatever the
// depth complexity: no view, no pixels, no peeling.

layout(local_size_x = 64) in;

// Triangle t's corners: b_corners[3t], b_corners[3t + 1], b_corners[3t + 2] (w unused).
layout(std430, binding = 0) readonly buffer Corners { vec4 b_corners[]; };
// Lane l of triangle t at b_terms[l * u_triangles + t]:
// lane 0 = (V, ∫x, ∫y, ∫z), lane 1 = (∫x², ∫y², ∫z², 0), lane 2 = (∫xy, ∫yz, ∫zx, 0).
layout(std430, binding = 1) writeonly buffer Terms { vec4 b_terms[]; };

uniform uint u_triangles;
// The first triangle of this dispatch: a large mesh takes several, each within the
// renderer's limit on work groups.
uniform uint u_first;

void main() {
    uint t = u_first + gl_GlobalInvocationID.x;
    if (t >= u_triangles) return;
    vec3 a = b_corners[3u * t].xyz;
    vec3 b = b_corners[3u * t + 1u].xyz;
    vec3 c = b_corners[3u * t + 2u].xyz;
    // Six times the signed volume of the tetrahedron (origin, a, b, c).
    float det = dot(a, cross(b, c));
    vec3 s = a + b + c;
    // ∫ x_i x_j dV = det / 120 (Σ_k v_ki v_kj + s_i s_j) over a tetrahedron with a vertex at 0.
    vec3 squares = a * a + b * b + c * c + s * s;
    vec3 products = a * a.yzx + b * b.yzx + c * c.yzx + s * s.yzx;
    b_terms[t] = vec4(det / 6.0, det / 24.0 * s);
    b_terms[u_triangles + t] = vec4(det / 120.0 * squares, 0.0);
    b_terms[2u * u_triangles + t] = vec4(det / 120.0 * products, 0.0);
}
