// The frame's materials (scene/material.h), one per document material (and
// one per mesh slot without one), in a storage buffer at binding 4
// (frame_blocks.glsl reserves it; render/gpu_material.h is the C++ side).
// A draw names its material with uMaterial; its textures are on units 0-2.
#ifndef HS_MATERIAL_BLOCK_GLSL
#define HS_MATERIAL_BLOCK_GLSL

const uint MAT_BASE_TEXTURE = 1u;
const uint MAT_NORMAL_MAP = 2u;
const uint MAT_HEIGHT_MAP = 4u;
const uint MAT_ALPHA_CUTOUT = 8u;
const uint MAT_TWO_SIDED = 16u;
const uint MAT_UNLIT = 32u;

struct Material {
  vec4 baseColor;  // rgb linear, a: opacity
  vec4 emission;   // rgb: colour x strength, a: alpha cut-out threshold
  vec4 surface;    // roughness, metallic, specular, shininess
  vec4 detail;     // normal strength, height scale (m), transmission (two-sided only), unused
  uvec4 kind;      // x: lighting model (MODEL_*), y: MAT_* flags
};
layout(std430, binding = 4) readonly buffer MaterialBlock { Material materials[]; };

uniform uint uMaterial;
layout(binding = 0) uniform sampler2D uBaseColorTexture;  // sRGB: sampled as linear
layout(binding = 1) uniform sampler2D uNormalMap;         // linear, tangent space, +Y up
layout(binding = 2) uniform sampler2D uHeightMap;         // linear, red = height, white is high

bool hasFlag(Material m, uint flag) { return (m.kind.y & flag) != 0u; }

#endif
