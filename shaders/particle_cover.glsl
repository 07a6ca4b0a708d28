// Which fragments of a particle's quad exist (render/particle_source.h):
// those where the sprite's alpha times the particle's opacity is visible.
// Included by particle.frag and, under HS_PARTICLE, by the transparency
// passes' own fragment shaders (abuffer_count.frag, abuffer_keys.frag,
// oit_kbuffer_depth.frag), so the passes that hand out nodes and slots see
// exactly the fragments the lit pass then colours. The sprite is read at
// an explicit level (particle.vert chose it from the particle's size on
// screen): no derivatives, so helper invocations cannot make two passes
// disagree.
#ifndef HS_PARTICLE_COVER_GLSL
#define HS_PARTICLE_COVER_GLSL

layout(binding = 0) uniform sampler2DArray uParticleSprites;  // sRGB, straight alpha (render/particle_sprites.h)
in vec2 vSpriteUv;
flat in float vSpriteLayer;
flat in float vSpriteLod;
flat in vec4 vParticleColour;  // linear RGB (HDR for fire), opacity

// Below this a fragment is dropped: the quads' empty corners would fill
// the K-buffer's slots and the A-buffer's nodes with nothing.
const float kParticleMinAlpha = 1.0 / 512.0;

vec4 particleSprite() { return textureLod(uParticleSprites, vec3(vSpriteUv, vSpriteLayer), vSpriteLod); }

void particleCoverDiscard() {
  if (particleSprite().a * vParticleColour.a < kParticleMinAlpha) discard;
}

#endif
