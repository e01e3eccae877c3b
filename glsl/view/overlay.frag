#version 330 core
// The viewer's text and insets: an RGBA image drawn pixel for pixel at u_origin, its alpha
// blending it over the frame.

uniform sampler2D u_image;
uniform ivec2 u_origin; // the image's bottom-left pixel in the target
out vec4 o_colour;

void main() {
    o_colour = texelFetch(u_image, ivec2(gl_FragCoord.xy) - u_origin, 0);
}
