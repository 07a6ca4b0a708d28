#version 450 core
// The cluster level view (render/cluster_source.h, RenderOptions::
// clusterLevels): each cluster of a hierarchy in its level's colour, level
// 0 (the scan's own triangles) green through yellow and orange to red and
// magenta for the coarsest, shaded by the sun so the shape stays readable.
// Written in scene units divided by the exposure, so the tone map shows
// the palette's colours.
#include "frame_blocks.glsl"
in vec3 vNormal;
uniform uint uLevel;
layout(location = 0) out vec4 outColor;

void main() {
  const vec3 palette[8] = vec3[](vec3(0.1, 0.75, 0.2), vec3(0.6, 0.85, 0.1), vec3(0.95, 0.85, 0.1),
                                 vec3(0.95, 0.55, 0.1), vec3(0.9, 0.25, 0.1), vec3(0.85, 0.1, 0.35),
                                 vec3(0.7, 0.1, 0.75), vec3(0.4, 0.2, 0.9));
  const vec3 c = palette[min(uLevel, 7u)];
  const vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
  const float light = 0.35 + 0.65 * max(dot(n, frame.sunDir.w > 0.0 ? normalize(frame.sunDir.xyz) : vec3(0.0, 0.0, 1.0)), 0.0);
  outColor = vec4(c * light / max(frame.params.y, 1e-20), 1.0);
}
