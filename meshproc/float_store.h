#pragma once
// A float value widened back to double after the store that rounded it.
// GCC 12's SLP vectorizer (-O3) was seen to forward the double value past
// such a store's rounding, in two places: the decimator's vertex records
// (the quadric's origin off the record's position by the rounding, about
// 1e-10 m on the bunny and 61 um at 500 m from the centre) and the
// refinement's test of a moved face (a face the test passed came out
// turned over once its corners were stored: test_meshproc_refine::
// noMoveTurnsAFaceAgainstTheOriginal). The empty asm makes the compiler
// assume the float may have changed, so it reloads it.
#include <glm/glm.hpp>

namespace hs::mesh {

inline glm::dvec3 reloaded(const glm::vec3& stored) {
#if defined(__GNUC__)
  asm volatile("" : : "r"(&stored) : "memory");
#endif
  return glm::dvec3(stored);
}

}  // namespace hs::mesh
