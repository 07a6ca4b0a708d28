#version 450 core
// Bins the frame's point and spot lights into one view's clusters
// (light_clusters.glsl): one invocation per cluster tests every light's
// range sphere against the cluster's view-space bounding box (the froxel's
// eight corners). The box holds the froxel, so no light that reaches a
// point of it is left out; the window of lights.glsl is exactly 0 at the
// range, so what the sphere leaves out is unlit anyway.
#include "frame_blocks.glsl"
#include "light_clusters.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 7) writeonly buffer LightGridOut { uint clusterCounts[]; };
layout(std430, binding = 9) writeonly buffer LightIndexOut { uint clusterLights[]; };
layout(std430, binding = 10) buffer LightCullStats { uint clustersOverCap; uint maxLightsInCluster; };
uniform mat4 uInvProjection;  // NDC -> view space of this view
uniform int uLightCount;

// The view-space point at distance d along the ray through NDC (x, y).
vec3 rayAt(vec2 ndc, float d) {
  vec4 p = uInvProjection * vec4(ndc, 0.5, 1.0);
  vec3 r = p.xyz / p.w;
  return r * (d / -r.z);
}

void main() {
  int cluster = int(gl_GlobalInvocationID.x);
  if (cluster >= LIGHT_CLUSTERS) return;
  ivec2 tile = ivec2(cluster % LIGHT_TILES_X, (cluster / LIGHT_TILES_X) % LIGHT_TILES_Y);
  int slice = cluster / (LIGHT_TILES_X * LIGHT_TILES_Y);
  vec2 lo = vec2(tile) / vec2(LIGHT_TILES_X, LIGHT_TILES_Y) * 2.0 - 1.0;
  vec2 hi = vec2(tile + 1) / vec2(LIGHT_TILES_X, LIGHT_TILES_Y) * 2.0 - 1.0;
  float dn = lightSliceStart(slice), df = lightSliceStart(slice + 1);
  vec3 bmin = vec3(1e38), bmax = vec3(-1e38);
  for (int c = 0; c < 4; ++c) {
    vec2 ndc = vec2((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y);
    vec3 a = rayAt(ndc, dn), b = rayAt(ndc, df);
    bmin = min(bmin, min(a, b));
    bmax = max(bmax, max(a, b));
  }
  mat3 toView = mat3(view.viewRotation);
  uint count = 0u;
  uint base = uint(cluster) * uint(LIGHT_CLUSTER_CAP);
  for (int i = 0; i < uLightCount; ++i) {
    vec3 c = toView * (lights[i].position.xyz - view.eyeOffset.xyz);
    float r = lights[i].position.w;
    vec3 d = c - clamp(c, bmin, bmax);
    if (dot(d, d) > r * r) continue;
    if (count < uint(LIGHT_CLUSTER_CAP)) clusterLights[base + count] = uint(i);
    ++count;
  }
  clusterCounts[cluster] = min(count, uint(LIGHT_CLUSTER_CAP));
  if (count > uint(LIGHT_CLUSTER_CAP)) {
    atomicAdd(clustersOverCap, 1u);
    atomicMax(maxLightsInCluster, count);
  }
}
