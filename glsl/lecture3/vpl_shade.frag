#version 330 core
// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): the picture, direct and gathered indirect light.
// The picture: direct light from the spot (shadowed by its depth image, the same image that
// holds the VPLs) plus the gathered indirect light, both reflected by the receiver's albedo,
// tone mapped (clamped, gamma 2.2).

uniform sampler2D u_receiver_position;
uniform sampler2D u_receiver_normal;
uniform sampler2D u_receiver_albedo;
uniform sampler2D u_gathered;     // irradiance from the VPLs
uniform sampler2D u_light_depth;  // the spot light's depth image
uniform mat4 u_light_view_projection;
uniform vec3 u_light_position;
uniform vec3 u_intensity;
uniform float u_direct;           // weights of the two terms (0 or 1)
uniform float u_indirect;
uniform float u_exposure;

out vec4 o_colour;

const float PI = 3.14159265358979;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 receiver = texelFetch(u_receiver_position, pixel, 0);
    if (receiver.w == 0.0) {
        o_colour = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    vec3 x = receiver.xyz;
    vec3 n = texelFetch(u_receiver_normal, pixel, 0).xyz;
    vec3 albedo = texelFetch(u_receiver_albedo, pixel, 0).rgb;
    vec3 direct = vec3(0.0);
    vec4 clip = u_light_view_projection * vec4(x, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    if (clip.w > 0.0 && all(lessThan(abs(ndc.xy), vec2(1.0)))) {
        ivec2 size = textureSize(u_light_depth, 0);
        ivec2 texel = clamp(ivec2((ndc.xy * 0.5 + 0.5) * vec2(size)), ivec2(0), size - 1);
        float stored = texelFetch(u_light_depth, texel, 0).r;
        if (ndc.z * 0.5 + 0.5 <= stored + 0.002) {
            vec3 to_light = u_light_position - x;
            float d2 = dot(to_light, to_light);
            direct = u_intensity * max(dot(n, to_light) / sqrt(d2), 0.0) / d2;
        }
    }
    vec3 indirect = texelFetch(u_gathered, pixel, 0).rgb;
    vec3 radiance = albedo / PI * (u_direct * direct + u_indirect * indirect);
    o_colour = vec4(pow(clamp(radiance * u_exposure, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
