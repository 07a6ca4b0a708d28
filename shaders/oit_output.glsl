// Included by mesh.frag under HS_OIT (before its main): the transparency
// and A-buffer variants of the mesh shader (render/oit.h, render/abuffer.h)
// run mesh.frag's shading unchanged, renamed meshShade here, and then do
// what oit_main.glsl's main does with the colour instead of writing it:
//   HS_OIT_ABUFFER   write into the A-buffer node that holds the fragment's key
//                    (abuffer_keys.frag; the fixed array too)
//   HS_OIT_KBUFFER   write into the K-buffer slot that holds the fragment's key
//   HS_OIT_WEIGHTED  weighted blended OIT's two targets
//   HS_OIT_PEEL      one depth-peeling layer: the nearest fragment behind the last layer
// With HS_OIT_TAIL what finds no place goes to the tail (oit_tail.glsl).
#ifndef HS_OIT_OUTPUT_GLSL
#define HS_OIT_OUTPUT_GLSL

#if defined(HS_OIT_ABUFFER) || defined(HS_OIT_KBUFFER) || defined(HS_OIT_WEIGHTED)
#include "abuffer.glsl"
#endif
#if defined(HS_OIT_ABUFFER) || defined(HS_OIT_KBUFFER)
// The depth test before the shader, as in the key pass that drew the same
// fragments (abuffer_keys.frag, oit_kbuffer_depth.frag): with the test
// after it, a fragment just behind the opaque surface (where a rasterizer's
// early depth and the shader's gl_FragCoord.z round apart, as around MSAA's
// resolved depth) would run, find no key and land in the tail.
layout(early_fragment_tests) in;
#endif
#ifdef HS_OIT_TAIL
#include "oit_tail.glsl"
#endif
// The key (and, for the K-buffer, its images). Outside any #ifdef: the
// shader library expands a file once, where it is first included.
#ifdef HS_OIT_ABUFFER
#define OIT_KEY_ONLY
#endif
#include "oit_kbuffer.glsl"
#ifdef HS_OIT_WEIGHTED
layout(location = 1) out float oitRevealage;
#endif
#ifdef HS_OIT_PEEL
layout(binding = 20) uniform sampler2D uOitPeeledDepth;  // the last layer's depth (1.0 before the first)
layout(binding = 21) uniform sampler2D uOitOpaqueDepth;
#endif

#define main meshShade

#endif
