// Paper 1 (Zhang & Kim 2007), section 6 "Stream Update": the min/max update of the AABB streams
// (Table II).
// Port of Zhang & Kim 2007 (IEEE TVCG 13(2)), Table II: "Stream update using a min/max
// operation in Cg". Our copy of the paper keeps the table's caption and Sec. 6's account of
// it, not the Cg lines themselves, so this port follows that account step by step: the
// single line drawn across the 1D render target makes one fragment per AABB k; it takes the
// column-wise minimum and maximum over the n_max texels of column k of the 2D vertex
// texture (Eq. 1), skipping empty texels (alpha 0), and writes them to COLOR0 (T_min) and
// COLOR1 (T_max) at once through multiple render targets.
#version 330 core

uniform sampler2D vertexTexture;
uniform int nMax;
layout(location = 0) out vec4 COLOR0;
layout(location = 1) out vec4 COLOR1;

// region: table2
void main()
{
  int k = int(gl_FragCoord.x);
  // Row 0 is never empty: every leaf has at least one triangle.
  vec3 lower = texelFetch(vertexTexture, ivec2(k, 0), 0).xyz;
  vec3 upper = lower;
  for (int i = 1; i < nMax; i++) {
    vec4 v = texelFetch(vertexTexture, ivec2(k, i), 0);
    if (v.a != 0.0) {
      lower = min(lower, v.xyz);
      upper = max(upper, v.xyz);
    }
  }
  COLOR0 = vec4(lower, 1.0);
  COLOR1 = vec4(upper, 1.0);
}
// endregion
