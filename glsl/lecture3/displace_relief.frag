// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006):
// relief mapping's search, the method it is compared with.
// Compiled after: glsl/lecture3/pixel_ray.glsl, glsl/lecture3/displace_normal.glsl
// Compiled after: glsl/lecture3/displace_common.glsl
// Relief mapping's search [Policarpo, Oliveira & Comba, I3D 2005], the method pyramidal
// displacement mapping is compared with: the ray's segment inside the box is sampled in
// u_linear_steps equal steps until a sample lies at or below the height field, then the last
// step is halved u_binary_steps times. The height field is the same bilinear field
// (interpolated in the shader from texelFetch, not by the texture unit). A step can jump over
// a thin feature: at grazing angles the hit lands behind it, or is missed.
// (The fragment stage is pixel_ray.glsl, displace_normal.glsl, displace_common.glsl, then
// this file.)

uniform int u_linear_steps;
uniform int u_binary_steps;

// Whether the point at parameter t of the ray lies at or under the height field.
bool below(Ray r, float t) {
    vec3 q = r.o + t * r.d;
    return q.z <= height_at(q.xy);
}

void main() {
    // The ray's segment inside the box; a pixel whose ray misses it shows nothing.
    Ray r = pixel_ray();
    vec2 box = box_interval(r);
    if (box.x > box.y) discard;
    // Linear search: equal steps from the entry until a sample is under the surface.
    float step = (box.y - box.x) / float(u_linear_steps);
    float above = box.x;
    float hit = -1.0;
    for (int i = 0; i <= u_linear_steps; ++i) {
        float t = box.x + step * float(i);
        if (below(r, t)) {
            hit = t;
            break;
        }
        above = t;
    }
    if (hit < 0.0) discard;
    // A hit at the entry is the box's wall; otherwise the binary search halves the last
    // step, keeping `above` over the surface and `hit` under it.
    bool wall = hit == box.x && enters_through_side(r);
    if (!wall) {
        for (int i = 0; i < u_binary_steps; ++i) {
            float mid = 0.5 * (above + hit);
            if (below(r, mid)) hit = mid; else above = mid;
        }
    }
    write_hit(r, hit, wall, float(u_linear_steps + u_binary_steps));
}
