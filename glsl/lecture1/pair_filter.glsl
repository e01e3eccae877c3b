// Lecture 1: the pair test that both formulations of the pairwise triangle tests share (a
// reconstruction of Choi, Kim & Kim 2006, lecture1-sources.md, section 3): the classic
// fragment shader (pair_test.frag) and its compute counterpart (pair_test.comp) include it
// first. No #version: the stage's own file carries it.
//
// The test is paper 1's exact test (Guigue & Devillers' orientation-only form of Möller's
// test) with each orientation sign computed in fp32 beside a bound on its error: a sign is
// used only when the value is larger than the bound, and any sign the bound leaves open
// makes the pair "may intersect". So a pair is dropped only when it is certainly disjoint,
// and what is reported is a superset of the exact answer.

const int UNSURE = 0;

// ---- A filtered orientation: the sign of ((b - a) x (c - a)) . (d - a), or UNSURE.
// The bound is Shewchuk's for orient3d (a multiple of the unit roundoff times the sum of the
// absolute values of the determinant's products), with a wide factor (2^-10 instead of
// about 7 * 2^-24): OpenGL 3.3 does not require correctly rounded arithmetic, only a relative
// accuracy near 10^-5 per operation. The absolute term covers products that underflow.
int orient(vec3 a, vec3 b, vec3 c, vec3 d) {
    vec3 ba = b - a, ca = c - a, da = d - a;
    vec3 n = cross(ba, ca);
    float det = dot(n, da);
    vec3 perm = vec3(abs(ba.y * ca.z) + abs(ba.z * ca.y),
                     abs(ba.z * ca.x) + abs(ba.x * ca.z),
                     abs(ba.x * ca.y) + abs(ba.y * ca.x));
    float bound = dot(perm, abs(da)) * 0.0009765625 + 1e-30;
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return UNSURE;
}

// ---- CHECK_MIN_MAX: the segments the triangles cut from their planes' common line
// overlap unless one of two orientations is certainly positive.
bool may_overlap(vec3 p1, vec3 q1, vec3 r1, vec3 p2, vec3 q2, vec3 r2) {
    return orient(q1, p2, p1, q2) != 1 && orient(p1, p2, r1, r2) != 1;
}

// ---- TRI_TRI_3D: triangle 2 permuted so that p2 is alone on its side of plane 1.
bool tri_tri_3d(vec3 p1, vec3 q1, vec3 r1, vec3 p2, vec3 q2, vec3 r2, ivec3 d) {
    if (d.x > 0) {
        if (d.y > 0) return may_overlap(p1, r1, q1, r2, p2, q2);
        if (d.z > 0) return may_overlap(p1, r1, q1, q2, r2, p2);
        return may_overlap(p1, q1, r1, p2, q2, r2);
    }
    if (d.y < 0) return may_overlap(p1, q1, r1, r2, p2, q2);
    if (d.z < 0) return may_overlap(p1, q1, r1, q2, r2, p2);
    return may_overlap(p1, r1, q1, p2, q2, r2);
}

// ---- Guigue & Devillers on the coordinates, each sign filtered.
bool may_intersect(vec3 p1, vec3 q1, vec3 r1, vec3 p2, vec3 q2, vec3 r2) {
    // Sides of triangle 1's corners with respect to plane 2: all on one side, disjoint.
    ivec3 d1 = ivec3(orient(p2, q2, r2, p1), orient(p2, q2, r2, q1), orient(p2, q2, r2, r1));
    if (d1.x == UNSURE || d1.y == UNSURE || d1.z == UNSURE) return true;
    if (d1.x == d1.y && d1.x == d1.z) return false;
    ivec3 d2 = ivec3(orient(p1, q1, r1, p2), orient(p1, q1, r1, q2), orient(p1, q1, r1, r2));
    if (d2.x == UNSURE || d2.y == UNSURE || d2.z == UNSURE) return true;
    if (d2.x == d2.y && d2.x == d2.z) return false;
    // Permute triangle 1 so that p1 is alone on its side, flipping triangle 2 to match.
    bool flip;
    vec3 a, b, c;
    if (d1.x > 0) {
        if (d1.y > 0)      { a = r1; b = p1; c = q1; flip = true; }
        else if (d1.z > 0) { a = q1; b = r1; c = p1; flip = true; }
        else               { a = p1; b = q1; c = r1; flip = false; }
    } else {
        if (d1.y < 0)      { a = r1; b = p1; c = q1; flip = false; }
        else if (d1.z < 0) { a = q1; b = r1; c = p1; flip = false; }
        else               { a = p1; b = q1; c = r1; flip = true; }
    }
    if (flip) return tri_tri_3d(a, b, c, p2, r2, q2, d2.xzy);
    return tri_tri_3d(a, b, c, p2, q2, r2, d2);
}

// ---- Scaling by a power of two is exact: the pair is brought to unit size so that the
// determinants' products neither overflow nor underflow at extreme coordinate scales.
int exponent_of(float m) {
    return ((floatBitsToInt(m) >> 23) & 255) - 127;
}

// 2^k for -126 <= k <= 127, built from its bits (exp2 need not be exact).
float power_of_two(int k) {
    return intBitsToFloat((k + 127) << 23);
}

// ---- One pair: triangle a (corners a0..a2, welded vertex ids in w) against triangle b.
// False only when the pair is certainly disjoint, or (self) when the two share a vertex.
bool pair_may_intersect(vec4 a0, vec4 a1, vec4 a2, vec4 b0, vec4 b1, vec4 b2, bool self_test) {
    // Neighbours (a shared welded vertex) are not tested against each other.
    if (self_test) {
        vec3 ids = vec3(a0.w, a1.w, a2.w);
        if (any(equal(ids, vec3(b0.w))) || any(equal(ids, vec3(b1.w))) || any(equal(ids, vec3(b2.w))))
            return false;
    }
    // Box reject: comparisons are exact, so a pair whose boxes are apart is disjoint.
    vec3 lo_a = min(a0.xyz, min(a1.xyz, a2.xyz)), hi_a = max(a0.xyz, max(a1.xyz, a2.xyz));
    vec3 lo_b = min(b0.xyz, min(b1.xyz, b2.xyz)), hi_b = max(b0.xyz, max(b1.xyz, b2.xyz));
    if (any(greaterThan(lo_a, hi_b)) || any(greaterThan(lo_b, hi_a)))
        return false;
    // Unit scale, in two exact steps (each factor a normal float).
    vec3 m3 = max(max(abs(lo_a), abs(hi_a)), max(abs(lo_b), abs(hi_b)));
    int e = exponent_of(max(m3.x, max(m3.y, m3.z)));
    float s1 = power_of_two(-e / 2), s2 = power_of_two(-e - (-e / 2));
    vec3 p1 = a0.xyz * s1 * s2, q1 = a1.xyz * s1 * s2, r1 = a2.xyz * s1 * s2;
    vec3 p2 = b0.xyz * s1 * s2, q2 = b1.xyz * s1 * s2, r2 = b2.xyz * s1 * s2;
    return may_intersect(p1, q1, r1, p2, q2, r2);
}
