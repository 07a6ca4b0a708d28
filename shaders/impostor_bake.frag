#version 450 core
// Bakes one frame of an octahedral impostor (render/impostor_cache.h):
// the unlit base colour (material colour x texture) and the normal and
// depth of the surface nearest the frame's viewer. Both targets hold
// coverage-weighted values (the clear is all zeros), so a mipmap's texel
// at a silhouette averages to coverage x value and the drawing divides by
// coverage (shaders/impostor.frag):
//   0 (sRGB)  rgb: base colour, a: coverage (1 where the mesh is)
//   1         rgb: normal (mesh space, facing the viewer) x 0.5 + 0.5,
//             a: depth along the frame's direction, 0 at the far pole of
//             the bounding sphere, 1 at the near one
// What mesh.frag drops is dropped here too: cut-out texels under the
// material's threshold. A translucent material (opacity under 1, drawn by
// the transparency passes) counts where its opacity is at least one half.
#include "material_block.glsl"
#include "mesh_uv.glsl"

in vec3 vNormal;
in vec2 vUv;
uniform vec3 uFrameDir;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormalDepth;

void main() {
  Material m = materials[uMaterial];
  vec4 texel = hasFlag(m, MAT_BASE_TEXTURE) ? texture(uBaseColorTexture, meshUv(vUv)) : vec4(1.0);
  vec4 base = m.baseColor * texel;
  if (hasFlag(m, MAT_ALPHA_CUTOUT) ? base.a < m.emission.a : m.baseColor.a < 0.5) discard;
  vec3 n = normalize(vNormal);
  if (dot(n, uFrameDir) < 0.0) n = -n;  // the side the frame sees
  outAlbedo = vec4(base.rgb, 1.0);
  // The depth target's 0.5 + 0.499 dot(q, d) back to 0.5 + 0.5 dot(q, d).
  outNormalDepth = vec4(n * 0.5 + 0.5, clamp(0.5 + (gl_FragCoord.z - 0.5) * (0.5 / 0.499), 0.0, 1.0));
}
