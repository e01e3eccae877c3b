#version 330 core
// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 5.3 "Simulation example" (Fig. 9): the
// bodies' shading in the frames.
// Lambert shading with a fixed sun; below the water line the colour is tinted blue-green.
uniform vec3 u_colour;
uniform float u_water_level;
in vec3 v_normal;
in float v_height;
out vec4 o_colour;
void main()
{
    // Lambert term with an ambient floor.
    vec3 sun = normalize(vec3(0.4, -0.5, 0.8));
    float light = 0.35 + 0.65 * max(dot(normalize(v_normal), sun), 0.0);
    vec3 c = u_colour * light;
    // Under the water line: the colour pulled towards the water's.
    if (v_height < u_water_level) c = mix(c, vec3(0.05, 0.25, 0.35), 0.45);
    o_colour = vec4(c, 1.0);
}
