#pragma once
// Resampling a row-major float grid to another size, corner-aligned: the
// first and last samples of the output sit on the first and last samples of
// the input (a terrain's extent is first-to-last sample), so the ground size
// does not change with the resolution.
#include <vector>

namespace hs::terrain {

enum class Resampling { Nearest, Bilinear, Cubic };
const char* resamplingName(Resampling r);

// Cubic is Catmull-Rom (interpolating: passes through the input samples; may
// overshoot a little at sharp steps, like every interpolating cubic).
std::vector<float> resampleGrid(const std::vector<float>& src, int w, int h, int outW, int outH, Resampling method);

}  // namespace hs::terrain
