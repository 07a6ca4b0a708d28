#include "mesh/procedural_textures.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace hs::mesh {
namespace {

Texture grey(int size, const std::vector<float>& h, const char* name) {
  Texture t;
  t.name = name;
  t.width = t.height = size;
  t.rgba.resize(size_t(size) * size_t(size) * 4);
  for (size_t i = 0; i < h.size(); ++i) {
    const uint8_t v = uint8_t(std::lround(std::clamp(h[i], 0.0f, 1.0f) * 255.0f));
    t.rgba[i * 4] = t.rgba[i * 4 + 1] = t.rgba[i * 4 + 2] = v;
    t.rgba[i * 4 + 3] = 255;
  }
  return t;
}

float smoothstep01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 374761393u + y * 668265263u + seed * 2246822519u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return h ^ (h >> 16);
}

uint8_t srgbByte(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  const float s = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(s * 255.0f));
}

}  // namespace

Texture brickHeightMap(int size, int rows, int columns, float bevel) {
  size = std::max(size, 4);
  rows = std::max(rows, 1);
  columns = std::max(columns, 1);
  std::vector<float> h(size_t(size) * size_t(size));
  const float mortar = 0.06f;  // of a brick's height, each side
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float fy = (float(y) + 0.5f) / float(size) * float(rows);
      const int row = int(fy);
      // Running bond: every other course shifted by half a brick.
      float fx = (float(x) + 0.5f) / float(size) * float(columns) + (row % 2 ? 0.5f : 0.0f);
      fx -= std::floor(fx);
      const float inRow = fy - float(row);
      // Distance to the brick's edge, in brick heights (a brick is columns/rows times wider).
      const float aspect = float(rows) / float(columns);
      const float dx = std::min(fx, 1.0f - fx) / aspect, dy = std::min(inRow, 1.0f - inRow);
      const float d = std::min(dx, dy) - mortar;
      h[size_t(y) * size_t(size) + size_t(x)] = d <= 0.0f ? 0.0f : smoothstep01(d / bevel);
    }
  return grey(size, h, "bricks (height)");
}

Texture noiseHeightMap(int size, int octaves, uint32_t seed) {
  size = std::max(size, 4);
  std::vector<float> h(size_t(size) * size_t(size), 0.0f);
  float amplitude = 0.5f, total = 0.0f;
  for (int o = 0, cells = 4; o < std::max(octaves, 1); ++o, cells *= 2, amplitude *= 0.5f) {
    total += amplitude;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const float fx = float(x) / float(size) * float(cells), fy = float(y) / float(size) * float(cells);
        const int x0 = int(fx), y0 = int(fy);
        const float tx = smoothstep01(fx - float(x0)), ty = smoothstep01(fy - float(y0));
        auto at = [&](int cx, int cy) {
          return float(hash(uint32_t(cx % cells), uint32_t(cy % cells), seed + uint32_t(o)) & 0xffff) / 65535.0f;
        };
        const float a = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * tx;
        const float b = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * tx;
        h[size_t(y) * size_t(size) + size_t(x)] += amplitude * (a + (b - a) * ty);
      }
  }
  for (float& v : h) v /= total;
  return grey(size, h, "noise (height)");
}

Texture stoneHeightMap(int size, int cells, uint32_t seed) {
  size = std::max(size, 4);
  cells = std::max(cells, 2);
  const Texture rough = noiseHeightMap(size, 5, seed + 101u);
  std::vector<float> h(size_t(size) * size_t(size));
  auto feature = [&](int cx, int cy) {
    const int wx = (cx % cells + cells) % cells, wy = (cy % cells + cells) % cells;
    const uint32_t r = hash(uint32_t(wx), uint32_t(wy), seed);
    return glm::vec2(float(cx) + 0.15f + 0.7f * float(r & 0xff) / 255.0f,
                     float(cy) + 0.15f + 0.7f * float((r >> 8) & 0xff) / 255.0f);
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec2 p((float(x) + 0.5f) / float(size) * float(cells), (float(y) + 0.5f) / float(size) * float(cells));
      float f1 = 1e9f, f2 = 1e9f;  // nearest and second-nearest stone centres (Worley)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const float d = glm::length(p - feature(int(std::floor(p.x)) + dx, int(std::floor(p.y)) + dy));
          if (d < f1) {
            f2 = f1;
            f1 = d;
          } else if (d < f2) {
            f2 = d;
          }
        }
      // Distance to the border between two stones: a dome that falls into the crevice.
      const float edge = smoothstep01((f2 - f1) / 0.45f);
      const float dome = std::sqrt(edge);
      const float grain = float(rough.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4]) / 255.0f;
      h[size_t(y) * size_t(size) + size_t(x)] = dome * (0.8f + 0.2f * grain);
    }
  return grey(size, h, "stones (height)");
}

Texture normalMapFromHeight(const Texture& height, float relief) {
  Texture t;
  t.name = "normals of " + height.name;
  t.width = height.width;
  t.height = height.height;
  t.rgba.resize(height.rgba.size());
  const int w = height.width, hgt = height.height;
  if (w <= 0 || hgt <= 0 || height.rgba.size() != size_t(w) * size_t(hgt) * 4) return t;
  auto at = [&](int x, int y) {
    x = (x % w + w) % w;
    y = (y % hgt + hgt) % hgt;
    return float(height.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4]) / 255.0f;
  };
  // Heights in units of the image's width: white is `relief` high.
  const float scale = relief * float(w);
  for (int y = 0; y < hgt; ++y)
    for (int x = 0; x < w; ++x) {
      const float dhdx = (at(x + 1, y) - at(x - 1, y)) * 0.5f * scale;
      // Rows run down the image: the slope towards its "up" is minus the slope along rows.
      const float dhdup = -(at(x, y + 1) - at(x, y - 1)) * 0.5f * scale;
      const glm::vec3 n = glm::normalize(glm::vec3(-dhdx, -dhdup, 1.0f));
      uint8_t* p = &t.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4];
      for (int c = 0; c < 3; ++c) p[c] = uint8_t(std::lround((n[c] * 0.5f + 0.5f) * 255.0f));
      p[3] = 255;
    }
  return t;
}

Texture tintByHeight(const Texture& height, glm::vec3 dark, glm::vec3 light) {
  Texture t;
  t.name = "colour of " + height.name;
  t.width = height.width;
  t.height = height.height;
  t.rgba.resize(height.rgba.size());
  for (size_t i = 0; i + 3 < height.rgba.size(); i += 4) {
    const glm::vec3 c = glm::mix(dark, light, float(height.rgba[i]) / 255.0f);
    for (int k = 0; k < 3; ++k) t.rgba[i + size_t(k)] = srgbByte(c[k]);
    t.rgba[i + 3] = 255;
  }
  return t;
}

}  // namespace hs::mesh
