#version 450 core
// CDLOD terrain (render/terrain_lod.h): one grid of G/2 x G/2 quads drawn
// once per selected node quadrant (instanced), its vertices on the terrain's
// samples, odd vertices morphing onto their even neighbours as the distance
// approaches the end of their level's range.
//
// Camera-relative without a large number in sight: a vertex's position
// relative to the LOD camera is (its sample - the camera's whole sample) *
// spacing - the camera's remainder. Both differences are small near the
// camera, and a vertex shared by two quadrants is computed from the same
// integers in both, so they agree to the bit (no cracks from rounding).
// The LOD camera is the frame's (mono) camera: both eyes of a stereo pair
// morph alike and differ only by their small eye offset (uEyeFromLod).
#include "frame_blocks.glsl"

layout(location = 0) in ivec2 aGrid;   // 0..G/2
layout(location = 1) in ivec4 aPatch;  // per instance: x0, y0 (samples), scale (samples per quad), level

uniform sampler2D uHeight;             // R32F: heights relative to the terrain origin
uniform ivec2 uSamples;
uniform vec2 uSpacing;                 // metres per sample
uniform ivec2 uCameraSample;           // the LOD camera's position in whole samples
uniform vec3 uCameraRest;              // LOD camera position minus uCameraSample * spacing (z: height above the origin)
uniform vec3 uEyeFromLod;              // this view's eye minus the LOD camera (metres)
uniform vec2 uMorph[16];               // per level: morph start (m), 1 / (range end - start)

out vec3 vEyePos;
out vec2 vSample;   // sample-space position (normals, paint weights, holes)
out vec2 vLocal;    // metres from the terrain origin (material tiling)

float heightAt(ivec2 s) { return texelFetch(uHeight, clamp(s, ivec2(0), uSamples - 1), 0).r; }

void main() {
  const int scale = aPatch.z;
  const ivec2 s = aPatch.xy + aGrid * scale;
  const float h = heightAt(s);
  const vec2 relS = vec2(s - uCameraSample);
  const float d = length(vec3(relS * uSpacing - uCameraRest.xy, h - uCameraRest.z));
  const vec2 m = uMorph[aPatch.w];
  const float k = clamp((d - m.x) * m.y, 0.0, 1.0);
  // Odd vertices of this level slide onto the even vertex below them: at
  // k = 1 the quads fold into the next level's triangles (same split).
  const ivec2 odd = (s / scale) & 1;
  const ivec2 t = s - odd * scale;
  const float ht = heightAt(t);
  const vec2 rel = mix(relS, vec2(t - uCameraSample), k);
  const vec3 p = vec3(rel * uSpacing - uCameraRest.xy, mix(h, ht, k) - uCameraRest.z) - uEyeFromLod;
  vSample = mix(vec2(s), vec2(t), k);
  vLocal = vSample * uSpacing;
  vEyePos = p;
  gl_Position = view.projection * (view.viewRotation * vec4(p, 1.0));
}
