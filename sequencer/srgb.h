#pragma once
// sRGB <-> linear for 8-bit pixels through tables: layouts (squeezing) and
// anaglyphs mix colours, which is only right in linear light, and must do
// it for 2 million pixels a frame.
#include <cstdint>

namespace hs::sequencer {

float srgb8ToLinear(uint8_t v);          // exact table of the sRGB curve
uint8_t linearToSrgb8(float linear);     // clamped to [0,1]; through a 16-bit table
float linearToSrgbFloat(float linear);   // the exact curve
float srgbFloatToLinear(float srgb);

}  // namespace hs::sequencer
