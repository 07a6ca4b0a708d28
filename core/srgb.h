#pragma once
// The sRGB transfer curve (IEC 61966-2-1), the one copy for every library:
// 8-bit pixels through exact tables (layouts, anaglyphs and writers convert
// 2 million pixels a frame), floats through the exact curve (material
// colours, the editor's colour pickers).
#include <cstdint>

namespace hs {

float srgb8ToLinear(uint8_t v);          // exact table of the sRGB curve
uint8_t linearToSrgb8(float linear);     // clamped to [0,1]; through a 16-bit table
float linearToSrgbFloat(float linear);   // the exact curve, clamped to [0,1]
float srgbFloatToLinear(float srgb);     // the exact curve
double linearToSrgb(double linear);      // the same in double, clamped to [0,1]
double srgbToLinear(double srgb);

}  // namespace hs
