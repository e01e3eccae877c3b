// Relief mapping's search [Policarpo, Oliveira & Comba, I3D 2005], the method pyramidal
// displacement mapping is compared with: the ray's segment inside the box is sampled in
// u_linear_steps equal steps until a sample lies at or below the height field, then the last
// step is halved u_binary_steps times. The height field is the same bilinear field
// (interpolated in the shader from texelFetch, not by the texture unit). A step can jump over
// a thin feature: at grazing angles the hit lands behind it, or is missed.
// (The fragment stage is displace_common.glsl followed by this file.)

uniform int u_linear_steps;
uniform int u_binary_steps;

bool below(Ray r, float t) {
    vec3 q = r.o + t * r.d;
    return q.z <= height_at(q.xy);
}

void main() {
    Ray r = pixel_ray();
    vec2 box = box_interval(r);
    if (box.x > box.y) discard;
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
    bool wall = hit == box.x && enters_through_side(r);
    if (!wall) {
        for (int i = 0; i < u_binary_steps; ++i) {
            float mid = 0.5 * (above + hit);
            if (below(r, mid)) hit = mid; else above = mid;
        }
    }
    write_hit(r, hit, wall, float(u_linear_steps + u_binary_steps));
}
