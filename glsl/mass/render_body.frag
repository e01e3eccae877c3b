#version 330 core
// Lambert shading with a fixed sun; below the water line the colour is tinted blue-green.
uniform vec3 color;
uniform float water_level;
in vec3 normal;
in float height;
out vec4 frag;
void main()
{
    vec3 sun = normalize(vec3(0.4, -0.5, 0.8));
    float light = 0.35 + 0.65 * max(dot(normalize(normal), sun), 0.0);
    vec3 c = color * light;
    if (height < water_level) c = mix(c, vec3(0.05, 0.25, 0.35), 0.45);
    frag = vec4(c, 1.0);
}
