#version 450 core
// Particle billboards (render/particle_source.h, particle.vert): the
// sprite times the particle's colour, lit like a translucent surface facing
// the camera (sun with its shadows, the scene's lights, sky ambient) or,
// unlit, as emitted light (HDR values above 1 for fire); faded where it
// nears the opaque surface behind it (soft particles); then stored as a
// translucent fragment by the frame's transparency mode (oit_store.glsl).
// Variants: HS_OIT with HS_OIT_ABUFFER / _KBUFFER / _WEIGHTED / _PEEL as
// for mesh.frag. An additive particle stores opacity -1 (oit_composite.glsl:
// it adds its light and hides nothing).
#include "lighting.glsl"
#ifdef HS_OIT
#include "oit_output.glsl"
#undef main  // oit_output.glsl renames mesh.frag's main; this shader has its own
#endif
#include "particle_cover.glsl"

in vec3 vEyePos;
flat in uint vObject;
layout(location = 0) out vec4 outColor;

#ifdef HS_OIT
#include "oit_store.glsl"
#endif

uniform bool uLit;
uniform bool uAdditive;
uniform float uSoftDistance;  // metres; 0: a hard edge where the quad meets the opaque surface
#ifndef HS_OIT_PEEL
// The opaque depth the pass tests against (the depth peel reads its own,
// oit_output.glsl's uOitOpaqueDepth).
layout(binding = 1) uniform sampler2D uParticleSceneDepth;
#endif

// Reversed-Z depth to the distance along the view axis (m), from the view's
// projection: depth = (P22 z + P32) / -z.
float viewDistance(float depth) { return view.projection[3][2] / max(depth + view.projection[2][2], 1e-30); }

float softFade() {
  if (uSoftDistance <= 0.0) return 1.0;
#ifdef HS_OIT_PEEL
  const float scene = texelFetch(uOitOpaqueDepth, ivec2(gl_FragCoord.xy), 0).r;
#else
  const float scene = texelFetch(uParticleSceneDepth, ivec2(gl_FragCoord.xy), 0).r;
#endif
  if (scene <= 0.0) return 1.0;  // the far plane: sky behind
  return clamp((viewDistance(scene) - viewDistance(gl_FragCoord.z)) / uSoftDistance, 0.0, 1.0);
}

void main() {
#ifdef HS_OIT_PEEL
  // As oit_main.glsl: only the nearest fragment behind the last peeled layer.
  const ivec2 p = ivec2(gl_FragCoord.xy);
  if (gl_FragCoord.z <= texelFetch(uOitOpaqueDepth, p, 0).r) discard;
  if (gl_FragCoord.z >= texelFetch(uOitPeeledDepth, p, 0).r) discard;
#endif
  particleCoverDiscard();  // the fragments the key and count passes saw
  const vec4 sprite = particleSprite();
  const vec3 albedo = vParticleColour.rgb * sprite.rgb;
  vec3 colour;
  if (uLit) {
    Surface s;
    s.position = vEyePos;
    s.view = normalize(-vEyePos);
    s.normal = s.view;  // a thin translucent card facing the camera
    s.albedo = albedo;
    s.roughness = 1.0;
    s.metallic = 0.0;
    s.specular = 0.0;
    s.shininess = 1.0;
    s.emission = vec3(0.0);
    s.transmission = 0.0;
    s.model = MODEL_LAMBERT;
    colour = shadeSurface(s);
  } else {
    colour = applyFog(albedo, vEyePos);
  }
  const float opacity = clamp(sprite.a * vParticleColour.a * softFade(), 0.0, 1.0);
  // Additive: the light a layer of this opacity would show, added (opacity -1).
  const vec4 c = uAdditive ? vec4(colour * opacity, -1.0) : vec4(colour, opacity);
#ifdef HS_OIT
  oitStore(c, vObject, length(vEyePos));
#else
  outColor = c;  // particles draw only in the transparency passes (render/particle_source.h)
#endif
}
