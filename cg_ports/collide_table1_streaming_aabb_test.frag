// Paper 1 (Zhang & Kim 2007), section 5.2 "Streaming AABB Overlap Tests", step 2 "Elementary AABB
// Overlap Test" (Table I).
// Port of Zhang & Kim 2007 (IEEE TVCG 13(2)), Table I: "Elementary AABB overlap test in Cg"
// (streamingAABBTest), line for line in GLSL 330. Cg's TEXCOORD0 / TEXCOORD1 inputs are the
// varyings uvA / uvB, tex1D is texture() on a sampler1D, and the COLOR output is `color`.
#version 330 core

in float uvA;
in float uvB;
out vec4 color;
uniform sampler1D minTextureA;
uniform sampler1D maxTextureA;
uniform sampler1D minTextureB;
uniform sampler1D maxTextureB;

// region: table1
void main()
{
  vec3 aabbMinA = texture(minTextureA, uvA).xyz;
  vec3 aabbMaxA = texture(maxTextureA, uvA).xyz;
  vec3 aabbMinB = texture(minTextureB, uvB).xyz;
  vec3 aabbMaxB = texture(maxTextureB, uvB).xyz;
  if (aabbMinA.x > aabbMaxB.x || aabbMaxA.x < aabbMinB.x ||
      aabbMinA.y > aabbMaxB.y || aabbMaxA.y < aabbMinB.y ||
      aabbMinA.z > aabbMaxB.z || aabbMaxA.z < aabbMinB.z)
    discard; // no overlap
  color = vec4(1.0, 0.0, 0.0, 0.0);
}
// endregion
