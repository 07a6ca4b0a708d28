// The K-buffer without interlock (docs/rendering.md "Transparency";
// render/oit.cpp): pass 1 (oit_kbuffer_depth.frag) inserts each fragment's
// key into its pixel's K sorted slots with a chain of atomicMin: slot i
// keeps the smaller of what it held and what arrives, the larger moves on
// to slot i+1. Whatever the order fragments arrive in, the slots end up
// holding the K smallest keys in order (each atomicMin is a compare-and-
// swap of a sorting network that cannot lose a key it has not pushed past
// the end). Pass 2 (mesh.frag's HS_OIT_KBUFFER) finds its key among the
// slots and writes its colour to that slot's layer; a key not among them
// goes to the tail (oit_tail.glsl). No fragment writes where another
// could, so nothing races and no interlock is needed.
//
// A key is the depth's bits inverted (reversed Z: nearer is smaller) with
// the lowest 8 bits replaced by a hash of the object and primitive, so two
// surfaces at one depth still have two keys and a fixed order. Fragments
// whose depths agree in the top 24 bits are ordered by that hash instead
// of depth (2^-15 relative); a full tie (same depth bits and hash) writes
// one slot twice, the only case left to arrival order.
#ifndef HS_OIT_KBUFFER_GLSL
#define HS_OIT_KBUFFER_GLSL

#define OIT_KEY_EMPTY 0xFFFFFFFFu

#ifndef OIT_KEY_ONLY  // the A-buffer uses the key alone
layout(binding = 2, r32ui) uniform coherent uimage2DArray uOitSlots;    // K keys per pixel, sorted
layout(binding = 3, rg32ui) uniform coherent uimage2DArray uOitColors;  // K colours (half pairs)
#endif
#ifndef OIT_K
#define OIT_K 8
#endif

uint oitKey(float depth, uint object, uint primitive) {
  const uint id = ((primitive * 0x9E3779B1u) ^ (object * 0x85EBCA77u)) >> 24;
  return min((~floatBitsToUint(depth) & 0xFFFFFF00u) | id, OIT_KEY_EMPTY - 1u);
}

#endif
