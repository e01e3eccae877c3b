#version 330 core
// When peeling ends [paper 4, section 3.2]: the tiles of the bodies still being peeled, as
// quads in clip space of the whole target (src/mass/peel_end.rs).
layout(location = 0) in vec2 a_clip;

void main()
{
    gl_Position = vec4(a_clip, 0.0, 1.0);
}
