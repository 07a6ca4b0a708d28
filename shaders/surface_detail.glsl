// Surface detail from a material's maps (material_block.glsl): the
// tangent frame, tangent-space normal mapping and parallax occlusion
// mapping. Included by mesh.frag in the variants HAS_NORMAL_MAP and
// HAS_PARALLAX only, so plain materials pay nothing.
//
// Conventions: tangents follow MikkTSpace (mesh/tangents.h), w * cross(N, T)
// is the direction of increasing v; v = 0 is the image's top row
// (mesh_data.h), so the image's "up", where an OpenGL-convention normal map
// points green, is the opposite: -w * cross(N, T).
#ifndef HS_SURFACE_DETAIL_GLSL
#define HS_SURFACE_DETAIL_GLSL
#include "material_block.glsl"

struct TangentFrame {
  vec3 t;   // +u
  vec3 up;  // the image's up (-v)
  vec3 n;
};

TangentFrame tangentFrame(vec3 n, vec4 tangent) {
  TangentFrame f;
  f.n = n;
  vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
  f.t = dot(t, t) > 1e-12 ? normalize(t) : normalize(abs(n.x) < 0.9 ? cross(n, vec3(1, 0, 0)) : cross(n, vec3(0, 1, 0)));
  f.up = -(tangent.w < 0.0 ? -1.0 : 1.0) * cross(n, f.t);
  return f;
}

// The normal a tangent-space normal map gives, its slopes scaled by `strength`.
vec3 normalFromMap(TangentFrame f, vec3 texel, float strength) {
  vec3 m = texel * 2.0 - 1.0;
  m.xy *= strength;
  vec3 n = m.x * f.t + m.y * f.up + max(m.z, 1e-3) * f.n;
  return normalize(n);
}

// Parallax occlusion mapping: steps along the view ray below the surface in
// layers (more when the view is grazing) until it passes under the height
// field (white is high, black `scale` below), then refines the crossing by
// bisection. `v` is the direction towards the eye in the tangent frame
// (x along t, y along up, z along n); `scale` the relief depth in UV units.
// Gradients are taken once outside the loops (their control flow is not
// uniform).
vec2 parallaxUv(vec2 uv, vec3 v, float scale) {
  if (scale <= 0.0 || v.z <= 1e-3) return uv;
  vec2 gx = dFdx(uv), gy = dFdy(uv);
  float steps = mix(48.0, 12.0, clamp(v.z, 0.0, 1.0));
  float layer = 1.0 / steps;
  // UV offset per unit of depth; the image's up is -v in UV.
  vec2 duv = vec2(v.x, -v.y) / max(v.z, 0.15) * scale * layer;
  vec2 cur = uv;
  float depth = 0.0;
  float below = 1.0 - textureGrad(uHeightMap, cur, gx, gy).r;
  for (int i = 0; i < 64 && depth < below; ++i) {
    cur -= duv;
    depth += layer;
    below = 1.0 - textureGrad(uHeightMap, cur, gx, gy).r;
  }
  vec2 a = cur + duv, b = cur;
  float da = depth - layer, db = depth;
  for (int i = 0; i < 6; ++i) {
    vec2 mid = 0.5 * (a + b);
    float dm = 0.5 * (da + db);
    if (dm < 1.0 - textureGrad(uHeightMap, mid, gx, gy).r) {
      a = mid;
      da = dm;
    } else {
      b = mid;
      db = dm;
    }
  }
  return 0.5 * (a + b);
}

// UV units per metre along the surface, from screen-space derivatives.
float uvPerMetre(vec2 uv, vec3 p) {
  float x = length(dFdx(uv)) / max(length(dFdx(p)), 1e-9);
  float y = length(dFdy(uv)) / max(length(dFdy(p)), 1e-9);
  return 0.5 * (x + y);
}

#endif
