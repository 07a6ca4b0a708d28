#pragma once
// How a render test compares a frame with its golden image under
// tests/render/golden (HS_GOLDEN_DIR and HS_TEST_OUT_DIR come from each test
// target's compile definitions, tests/render/CMakeLists.txt: the targets
// that compare with goldens).
#include <QtTest>

#include <string>

#include "core/image.h"
#include "image_compare.h"

namespace hs::test {

inline Rgba8Image toTest(const hs::Image& img) { return {img.width, img.height, img.rgba8}; }

// Fails the calling test function with checkGolden's message (the image's
// name, the difference against the tolerance, where the actual image went).
// Like any Qt Test check in a helper, a failure returns from here only: the
// caller goes on and the test is reported failed.
inline void verifyGolden(const std::string& name, const hs::Image& img, const GoldenTolerance& tol = {}) {
  const std::string problem = checkGolden(HS_GOLDEN_DIR, HS_TEST_OUT_DIR, name, toTest(img), tol);
  QVERIFY2(problem.empty(), problem.c_str());
}

}  // namespace hs::test
