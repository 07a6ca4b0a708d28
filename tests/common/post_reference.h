#pragma once
// The post chain's per-pixel effects on the CPU, in double (docs/rendering.md
// "Post-processing"; shaders/tonemap.frag is the GPU side): exposure,
// chromatic aberration (bilinear taps of the HDR image as GL samples them),
// the tone maps (none, ACES fitted, AgX, Khronos PBR Neutral), the grade,
// the LUT (given as a function), the vignette and grain, then sRGB
// encoding to 8 bits. Bloom is not here
// (its tests check what it does, not its arithmetic). What test_post_chain
// holds the renderer's output against.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/lowbias32.h"
#include "render/passes/output_passes.h"
#include "scene/light_units.h"
#include "scene/scene_state.h"

namespace hs::test {

inline glm::dvec3 acesFittedRef(glm::dvec3 x) {
  const double a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return glm::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

inline glm::dvec3 agxRef(glm::dvec3 c) {
  // Rows of the inset and outset matrices (the shader's GLSL mat3 is column-major: these are its columns).
  const double in[3][3] = {{0.842479062253094, 0.0423282422610123, 0.0423756549057051},
                           {0.0784335999999992, 0.878468636469772, 0.0784336},
                           {0.0792237451477643, 0.0791661274605434, 0.879142973793104}};
  const double out[3][3] = {{1.19687900512017, -0.0528968517574562, -0.0529716355144438},
                            {-0.0980208811401368, 1.15190312990417, -0.0980434501171241},
                            {-0.0990297440797205, -0.0989611768448433, 1.15107367264116}};
  auto apply = [](const double m[3][3], glm::dvec3 v) {  // column j of the GLSL matrix is m[j]
    glm::dvec3 r(0.0);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) r[i] += m[j][i] * v[j];
    return r;
  };
  const double minEv = -12.47393, maxEv = 4.026069;
  glm::dvec3 x = apply(in, glm::max(c, glm::dvec3(0.0)));
  for (int i = 0; i < 3; ++i) {
    double v = std::clamp(std::log2(std::max(x[i], 1e-10)), minEv, maxEv);
    v = (v - minEv) / (maxEv - minEv);
    const double v2 = v * v, v4 = v2 * v2;
    x[i] = 15.5 * v4 * v2 - 40.14 * v4 * v + 31.96 * v4 - 6.868 * v2 * v + 0.4298 * v2 + 0.1191 * v - 0.00232;
  }
  x = apply(out, x);
  for (int i = 0; i < 3; ++i) x[i] = std::pow(std::clamp(x[i], 0.0, 1.0), 2.2);
  return x;
}

inline glm::dvec3 pbrNeutralRef(glm::dvec3 c) {
  const double start = 0.8 - 0.04, desaturation = 0.15;
  const double x = std::min({c.r, c.g, c.b});
  const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  c -= offset;
  const double peak = std::max({c.r, c.g, c.b});
  if (peak < start) return glm::clamp(c, 0.0, 1.0);
  const double d = 1.0 - start;
  const double newPeak = 1.0 - d * d / (peak + d - start);
  c *= newPeak / peak;
  const double g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
  return glm::clamp(glm::mix(c, glm::dvec3(newPeak), g), 0.0, 1.0);
}

inline glm::dvec3 toneMapRef(scene::Tonemap t, glm::dvec3 c) {
  switch (t) {
    case scene::Tonemap::Aces: return acesFittedRef(c);
    case scene::Tonemap::AgX: return agxRef(c);
    case scene::Tonemap::PbrNeutral: return pbrNeutralRef(c);
    case scene::Tonemap::None: break;
  }
  return c;
}

inline uint32_t hashRef(uint32_t x) { return lowbias32(x); }

inline double srgbRef(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// GL's bilinear sample of channel `ch` of a top-row-first RGBA float image
// at texture coordinates uv (v up, clamped to the edge texels).
inline double bilinearRef(const Image& img, glm::dvec2 uv, int ch) {
  const double x = uv.x * img.width - 0.5, y = (1.0 - uv.y) * img.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = x - fx, ty = y - fy;
  auto at = [&](int px, int py) {
    px = std::clamp(px, 0, img.width - 1), py = std::clamp(py, 0, img.height - 1);
    return double(img.rgbaF[(size_t(py) * size_t(img.width) + size_t(px)) * 4 + size_t(ch)]);
  };
  const int ix = int(fx), iy = int(fy);
  // Rows top first: y grows downwards, so "iy + 1" is below.
  return (1 - ty) * ((1 - tx) * at(ix, iy) + tx * at(ix + 1, iy)) + ty * ((1 - tx) * at(ix, iy + 1) + tx * at(ix + 1, iy + 1));
}

inline double srgbToLinearRef(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

// A LUT on sRGB-encoded values in [0, 1] (OpenColorIO's CPU processor in
// test_post_lut).
using LutRef = std::function<glm::dvec3(glm::dvec3)>;

// The output (sRGB, 8 bits, top row first) of `hdr` (the renderer's linear
// HDR, before exposure) through the chain `settings` asks for, bloom left
// out, at frame number `frame`; `lut` stands for the stored LUT when
// settings.post.lutEnabled, `view` for the OpenColorIO view transform (in
// the tone map's place, its display code values decoded as sRGB) when
// settings.post.viewTransform.
inline Image postReference(const Image& hdr, const scene::SceneSettings& settings, int64_t frame,
                           const LutRef& lut = {}, const LutRef& view = {}) {
  const scene::PostSettings& post = settings.post;
  const double exposure = scene::exposureMultiplier(settings.exposureEv100);
  const bool ca = post.chromaticAberration && post.chromaticAberrationPx > 0.0f;
  const bool vignette = post.vignette && post.vignetteIntensity > 0.0f;
  const bool grain = post.grain && post.grainIntensity > 0.0f;
  const double lines = double(hdr.height) / 1080.0;
  const double caScale = double(post.chromaticAberrationPx) * lines / (0.5 * std::hypot(hdr.width, hdr.height));
  const glm::dvec3 wb = glm::dvec3(render::whiteBalanceGains(post.temperature, post.tint));
  glm::dvec2 aspect(double(hdr.width) / hdr.height, 1.0);
  aspect /= glm::length(aspect);
  const double cell = std::max(1.0, double(post.grainSizePx) * lines);
  Image out = Image::make8(hdr.width, hdr.height);
  for (int y = 0; y < hdr.height; ++y)
    for (int x = 0; x < hdr.width; ++x) {
      const size_t i = (size_t(y) * size_t(hdr.width) + size_t(x)) * 4;
      glm::dvec3 c(hdr.rgbaF[i], hdr.rgbaF[i + 1], hdr.rgbaF[i + 2]);
      const glm::dvec2 uv((x + 0.5) / hdr.width, 1.0 - (y + 0.5) / hdr.height);
      if (ca) {
        c.r = bilinearRef(hdr, glm::dvec2(0.5) + (uv - 0.5) * (1.0 + caScale), 0);
        c.b = bilinearRef(hdr, glm::dvec2(0.5) + (uv - 0.5) * (1.0 - caScale), 2);
      }
      if (post.viewTransform && view) {
        const glm::dvec3 code = view(c * exposure);
        for (int k = 0; k < 3; ++k) c[k] = srgbToLinearRef(code[k]);  // clamps to [0, 1] first
      } else {
        c = toneMapRef(settings.tonemap, c * exposure);
      }
      if (post.grade) {
        c *= wb;
        c = glm::clamp(glm::dvec3(post.gain) * c + glm::dvec3(post.lift) * (1.0 - c), 0.0, 1.0);
        for (int k = 0; k < 3; ++k) c[k] = std::pow(c[k], 1.0 / double(post.gamma[k]));
        const double luma = glm::dot(c, glm::dvec3(0.2126, 0.7152, 0.0722));
        c = glm::max(glm::mix(glm::dvec3(luma), c, double(post.saturation)), 0.0);
      }
      if (post.lutEnabled && lut) {
        glm::dvec3 e;
        for (int k = 0; k < 3; ++k) e[k] = srgbRef(c[k]);
        const glm::dvec3 looked = glm::mix(e, lut(e), double(post.lutIntensity));
        for (int k = 0; k < 3; ++k) c[k] = srgbToLinearRef(looked[k]);
      }
      if (vignette) {
        const double r = glm::length((uv - 0.5) * 2.0 * aspect);
        const double falloff = 1.0 / ((1.0 + r * r) * (1.0 + r * r));
        c *= glm::mix(1.0, (falloff - 0.25) / 0.75, double(post.vignetteIntensity));
      }
      if (grain) {
        const double l = std::clamp(glm::dot(c, glm::dvec3(0.2126, 0.7152, 0.0722)), 0.0, 1.0);
        // gl_FragCoord counts rows from the bottom.
        const uint32_t cx = uint32_t(std::floor((x + 0.5) / cell)), cy = uint32_t(std::floor((hdr.height - y - 0.5) / cell));
        const uint32_t h = hashRef(hashRef(hashRef(uint32_t(frame)) ^ cx) ^ (cy * 0x9e3779b9u));
        const double g = double(h >> 8) * (2.0 / 16777216.0) - 1.0;
        c *= 1.0 + double(post.grainIntensity) * g * 4.0 * (1.0 - l);
      }
      for (int k = 0; k < 3; ++k) out.rgba8[i + size_t(k)] = uint8_t(std::lround(srgbRef(c[k]) * 255.0));
      out.rgba8[i + 3] = 255;
    }
  return out;
}

}  // namespace hs::test
