#version 330 core
// Lecture 1, generalized Voronoi diagrams (Hoff et al. 1999, a reconstruction): instance i
// covers the whole domain for site i. Hoff draws each site's bounded distance mesh; here the
// rectangle is the domain and the fragment shader computes the distance exactly.

flat out int v_site;

void main() {
    v_site = gl_InstanceID;
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
