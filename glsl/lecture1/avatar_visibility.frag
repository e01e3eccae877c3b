#version 330 core
// Lecture 1, continuous collision for an avatar (Kim, Redon, Lin, Manocha & Templeman 2007):
// the visibility passes of the CULLIDE-style query (a reconstruction). Only the depth test
// and the occlusion query count; the colour is not kept (the target has none).

out vec4 o_colour;

void main() {
    o_colour = vec4(1.0);
}
