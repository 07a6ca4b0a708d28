// The UV a mesh's fragment shaders sample its textures at (mesh.frag,
// oit_main.glsl, shadow_depth.frag's cut-out): the interpolated UV held to
// the range its submesh's UVs span (uUvBounds: render/gpu_mesh_cache.h
// GpuMesh::uvBounds, set per draw by render/material_binding.cpp), widened
// on each side by the range's own extent.
//
// Inside a triangle the perspective-correct UV is a blend of its vertices'
// and lies in the range: nothing changes there. Fragment shaders also run
// for pixels off the triangle: the rest of a 2x2 quad (derivatives), on
// llvmpipe the rest of the 4x4 block it shades as one, and under MSAA a
// pixel with a sample on the triangle and its centre off it. Their UVs are
// extrapolated; off a triangle by up to its own size on screen they stay
// within the widened range, so the footprints of its edge pixels do not
// change either. But near the line where the triangle's plane vanishes (the
// interpolated 1/w goes through 0: a triangle seen edge-on, a leaf card
// side-on) they grow without bound. The texture unit takes the filter's
// footprint from the UV differences across the quad, and llvmpipe's
// anisotropic filter (mesh textures ask for 8x: gpu_mesh_cache.cpp) walks
// the footprint's whole bounding box texel by texel, up to 2^31 texels when
// its float-to-int conversion saturates: a field of junipers under MSAA 4x
// spent 150 s in a handful of such blocks. Held, two lanes' UVs differ by
// at most three extents, which bounds the walk: a few hundred texels for a
// leaf card's UVs (0..1). (textureGrad with bounded gradients does not
// help: llvmpipe's anisotropic path takes its derivatives from the
// coordinates.)
// A range of all zeros (a draw that sets none) leaves the UV as it is.
#ifndef HS_MESH_UV_GLSL
#define HS_MESH_UV_GLSL

uniform vec4 uUvBounds;  // min u, min v, max u, max v

vec2 meshUv(vec2 uv) {
  if (uUvBounds == vec4(0.0)) return uv;
  vec2 extent = uUvBounds.zw - uUvBounds.xy;
  vec2 c = clamp(uv, uUvBounds.xy - extent, uUvBounds.zw + extent);
  // 0 / 0 on the vanishing line itself; min and max need not pass NaN on.
  return any(isnan(c)) ? uUvBounds.xy : c;
}

#endif
