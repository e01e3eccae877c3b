#version 430 core
// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 2.1 "Computing mass properties with volume
// integrals", per triangle as a compute pass (then and now); with a clip against the water
// plane, the submerged part of section 5.2.
// The divergence-theorem sum written directly: one invocation per triangle (a, b, c) adds the
// signed tetrahedron (origin, a, b, c), whose integrals of 1, x, y, z, x², y², z², xy, yz, zx
// have closed forms. The sum over a closed surface is the solid's integrals, whatever the
// depth complexity: no view, no pixels, no peeling.
// A triangle marked for clipping keeps its part in z <= 0 (one or two triangles). The CPU put
// the origin on the water plane for such bodies, so the plane's cross-section, which closes
// the clipped surface, adds nothing: its tetrahedra (origin, cap triangle) are flat.

layout(local_size_x = 64) in;

// Triangle t's corners: b_corners[3t], b_corners[3t + 1], b_corners[3t + 2]. The first
// corner's w is 1 where the triangle is to be clipped to z <= 0, else 0.
layout(std430, binding = 0) readonly buffer Corners { vec4 b_corners[]; };
// Lane l of triangle t at b_terms[l * u_triangles + t]:
// lane 0 = (V, ∫x, ∫y, ∫z), lane 1 = (∫x², ∫y², ∫z², 0), lane 2 = (∫xy, ∫yz, ∫zx, 0).
// Without u_second_moments only lane 0 (eq. 4's four integrands, what buoyancy needs).
layout(std430, binding = 1) writeonly buffer Terms { vec4 b_terms[]; };

uniform uint u_triangles;
// The first triangle of this dispatch: a large mesh takes several, each within the
// renderer's limit on work groups.
uniform uint u_first;
uniform bool u_second_moments;

// The integrals of the signed tetrahedron (origin, a, b, c), added into the three lanes.
void add_tetrahedron(vec3 a, vec3 b, vec3 c, inout vec4 first, inout vec3 squares,
                     inout vec3 products) {
    // Six times the signed volume of the tetrahedron.
    float det = dot(a, cross(b, c));
    vec3 s = a + b + c;
    first += vec4(det / 6.0, det / 24.0 * s);
    // ∫ x_i x_j dV = det / 120 (Σ_k v_ki v_kj + s_i s_j) over a tetrahedron with a vertex at 0.
    squares += det / 120.0 * (a * a + b * b + c * c + s * s);
    products += det / 120.0 * (a * a.yzx + b * b.yzx + c * c.yzx + s * s.yzx);
}

// Where edge (below, above) crosses z = 0. Both triangles that share an edge see its ends in
// the same roles, so they get the same point bit for bit and the clipped surface stays closed.
vec3 crossing(vec3 below, vec3 above) {
    float t = below.z / (below.z - above.z);
    return vec3(mix(below.xy, above.xy, t), 0.0);
}

void main() {
    uint t = u_first + gl_GlobalInvocationID.x;
    if (t >= u_triangles) return;
    vec4 a4 = b_corners[3u * t];
    vec3 v[3] = vec3[3](a4.xyz, b_corners[3u * t + 1u].xyz, b_corners[3u * t + 2u].xyz);
    vec4 first = vec4(0.0);
    vec3 squares = vec3(0.0), products = vec3(0.0);
    if (a4.w == 0.0) {
        add_tetrahedron(v[0], v[1], v[2], first, squares, products);
    } else {
        // Sutherland-Hodgman against z <= 0: the kept corners and the crossings, in order
        // (at most four points), fanned from the first.
        vec3 p[4];
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            vec3 i = v[k], j = v[(k + 1) % 3];
            if (i.z <= 0.0) p[n++] = i;
            if (i.z < 0.0 && j.z > 0.0) p[n++] = crossing(i, j);
            if (i.z > 0.0 && j.z < 0.0) p[n++] = crossing(j, i);
        }
        for (int k = 1; k + 1 < n; ++k) {
            add_tetrahedron(p[0], p[k], p[k + 1], first, squares, products);
        }
    }
    b_terms[t] = first;
    if (u_second_moments) {
        b_terms[u_triangles + t] = vec4(squares, 0.0);
        b_terms[2u * u_triangles + t] = vec4(products, 0.0);
    }
}
