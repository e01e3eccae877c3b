#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006): the
// box the height field is traced in.
// The box the height field is laid on, without vertex buffers: 12 triangles made from
// gl_VertexID, counter-clockwise seen from outside, so that culling front faces leaves one
// fragment per pixel (the box is convex): its far side, which the near plane does not clip
// when the eye is close to the box. Each fragment then traces its own pixel's ray.

uniform mat4 u_view_projection;
uniform vec3 u_box; // (Lx, Ly, Lz), world units

const int CORNERS[36] = int[36](0, 2, 1, 1, 2, 3,   // z = 0
                                4, 5, 6, 5, 7, 6,   // z = Lz
                                0, 1, 4, 1, 5, 4,   // y = 0
                                2, 6, 3, 3, 6, 7,   // y = Ly
                                0, 4, 2, 2, 4, 6,   // x = 0
                                1, 3, 5, 3, 7, 5);  // x = Lx

void main() {
    int c = CORNERS[gl_VertexID];
    vec3 corner = vec3(float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1));
    gl_Position = u_view_projection * vec4(corner * u_box, 1.0);
}
