#pragma once
// The stylised effects (docs/rendering.md "Stylised effects";
// shaders/stylise.frag, shaders/kuwahara*.frag) written again on the CPU in
// double precision, from the image the chain hands them: the renderer's
// output with the effects off (8-bit, display-encoded, rows top-down as
// Renderer::readDisplay gives them). The Bayer matrix here is built by its
// recursive definition, not the shader's bit formula.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/srgb.h"
#include "scene/scene_state.h"

namespace hs::test {

namespace stylised_detail {

using Rgb = std::array<double, 3>;

// y up, clamped reads of an 8-bit image as 0..1.
struct Source8 {
  const Image& img;
  Rgb fetch(int x, int y) const {
    x = std::clamp(x, 0, img.width - 1);
    y = std::clamp(y, 0, img.height - 1);
    const uint8_t* p = &img.rgba8[(size_t(img.height - 1 - y) * size_t(img.width) + size_t(x)) * 4];
    return {p[0] / 255.0, p[1] / 255.0, p[2] / 255.0};
  }
  Rgb sample(double px, double py) const {
    const double fx = px - 0.5, fy = py - 0.5;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const double tx = fx - x0, ty = fy - y0;
    Rgb out{};
    const Rgb a = fetch(x0, y0), b = fetch(x0 + 1, y0), c = fetch(x0, y0 + 1), d = fetch(x0 + 1, y0 + 1);
    for (int i = 0; i < 3; ++i) out[i] = (a[i] * (1 - tx) + b[i] * tx) * (1 - ty) + (c[i] * (1 - tx) + d[i] * tx) * ty;
    return out;
  }
};

inline double luma(const Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
inline double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace stylised_detail

// The 8x8 Bayer index matrix by its recursive definition: M1 = [0 2; 3 1],
// M2n = [4M, 4M+2; 4M+3, 4M+1]; [row y][column x].
inline std::array<std::array<int, 8>, 8> bayerMatrix8() {
  std::vector<std::vector<int>> m{{0, 2}, {3, 1}};
  while (m.size() < 8) {
    const size_t n = m.size();
    std::vector<std::vector<int>> next(2 * n, std::vector<int>(2 * n));
    for (size_t y = 0; y < n; ++y)
      for (size_t x = 0; x < n; ++x) {
        next[y][x] = 4 * m[y][x];
        next[y][x + n] = 4 * m[y][x] + 2;
        next[y + n][x] = 4 * m[y][x] + 3;
        next[y + n][x + n] = 4 * m[y][x] + 1;
      }
    m = std::move(next);
  }
  std::array<std::array<int, 8>, 8> out{};
  for (size_t y = 0; y < 8; ++y)
    for (size_t x = 0; x < 8; ++x) out[y][x] = m[y][x];
  return out;
}

// The per-pixel pass (comic or outlines, CRT, dithering) on `in`, for an
// image of `in`'s size; `blueNoise`: the thresholds the renderer tiles
// (side x side, rows in y-up order as uploaded).
inline Image stylisePassReference(const Image& in, const scene::PostSettings& post, const std::vector<float>& blueNoise,
                                  int noiseSide) {
  using namespace stylised_detail;
  const Source8 src{in};
  const int w = in.width, h = in.height;
  const double lines = h / 1080.0;
  const auto bayer = bayerMatrix8();
  const Rgb outlineColour{linearToSrgb(post.outlineColor.r), linearToSrgb(post.outlineColor.g),
                          linearToSrgb(post.outlineColor.b)};
  // Reads as the pass reads: between pixels on the CRT's curved screen.
  auto at = [&](double px, double py) {
    return post.crt ? src.sample(px, py) : src.fetch(int(std::floor(px)), int(std::floor(py)));
  };
  auto sobel = [&](double px, double py) {
    auto l = [&](int dx, int dy) { return luma(at(px + dx, py + dy)); };
    const double gx = (l(1, 1) + 2 * l(1, 0) + l(1, -1)) - (l(-1, 1) + 2 * l(-1, 0) + l(-1, -1));
    const double gy = (l(-1, 1) + 2 * l(0, 1) + l(1, 1)) - (l(-1, -1) + 2 * l(0, -1) + l(1, -1));
    return std::hypot(gx, gy) * 0.25;
  };
  auto outline = [&](Rgb c, double px, double py) {
    const double th = std::max(1e-3, double(post.outlineThreshold));
    const double t = smoothstep(th, 1.5 * th, sobel(px, py));
    for (int i = 0; i < 3; ++i) c[i] = c[i] * (1 - t) + outlineColour[i] * t;
    return c;
  };
  Image out;
  out.width = w;
  out.height = h;
  out.rgba8.assign(size_t(w) * size_t(h) * 4, 255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double px = x + 0.5, py = y + 0.5;
      bool off = false;
      if (post.crt) {
        double cx = px / w * 2 - 1, cy = py / h * 2 - 1;
        const double k = 1 + double(post.crtCurvature) * (cx * cx + cy * cy);
        cx *= k, cy *= k;
        px = (cx * 0.5 + 0.5) * w, py = (cy * 0.5 + 0.5) * h;
        off = cx < -1 || cx > 1 || cy < -1 || cy > 1;
      }
      Rgb c = at(px, py);
      if (post.comic) {
        const double levels = std::max(double(post.comicLevels), 2.0) - 1.0;
        const double shade = luma(c);
        for (double& v : c) v = std::floor(v * levels + 0.5) / levels;
        const double cell = std::max(2.0, double(post.comicDotPx) * lines);
        const double fx = x + 0.5, fy = y + 0.5;
        // The grid turned 45 degrees (GLSL's mat2 is column by column).
        const double rx = (0.70710678 * fx - 0.70710678 * fy) / cell, ry = (0.70710678 * fx + 0.70710678 * fy) / cell;
        const double d = std::hypot(rx - std::floor(rx) - 0.5, ry - std::floor(ry) - 0.5);
        const double dark = std::clamp((0.6 - shade) / 0.6, 0.0, 1.0);
        const double radius = 0.7071 * std::sqrt(dark);
        const double ink = 1.0 - smoothstep(radius - 0.5 / cell, radius + 0.5 / cell, d);
        const double keep = 1.0 - 0.75 * ink * (dark >= 1e-4 ? 1.0 : 0.0);
        for (double& v : c) v *= keep;
        c = outline(c, px, py);
      } else if (post.outlines) {
        c = outline(c, px, py);
      }
      if (post.crt) {
        const double count = std::clamp(double(post.crtLinesPer1080), 1.0, std::max(1.0, double(float(lines) * 360.0f)));
        const double row = py / h * count;
        const double beam = 0.5 - 0.5 * std::cos(2 * M_PI * row);
        for (int i = 0; i < 3; ++i) {
          c[i] *= 1 - double(post.crtScanlines) * (1 - beam);
          if (i != x % 3) c[i] *= 1 - double(post.crtMask);
        }
        if (off) c = {0, 0, 0};
      }
      if (post.dither != scene::DitherMode::Off) {
        const double t = post.dither == scene::DitherMode::Bayer
                             ? (bayer[size_t(y % 8)][size_t(x % 8)] + 0.5) / 64.0
                             : double(blueNoise[size_t(y % noiseSide) * size_t(noiseSide) + size_t(x % noiseSide)]);
        const double steps = std::max(double(post.ditherLevels), 2.0) - 1.0;
        for (double& v : c) v = std::min(std::floor(std::clamp(v, 0.0, 1.0) * steps + t), steps) / steps;
      }
      uint8_t* o = &out.rgba8[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
      for (int i = 0; i < 3; ++i) o[i] = uint8_t(std::lround(std::clamp(c[i], 0.0, 1.0) * 255.0));
    }
  return out;
}

// Floyd-Steinberg error diffusion to `levels` per channel on `in`, rows in
// the order the GPU's wavefront finishes them (bottom row first, as GL
// numbers them), each left to right, in float with the additions in the
// shader's order.
inline Image errorDiffusionReference(const Image& in, double levels) {
  const int w = in.width, h = in.height;
  const float steps = float(std::max(levels, 2.0) - 1.0);
  std::vector<std::array<float, 3>> below(size_t(w) * 2, {0.0f, 0.0f, 0.0f});
  Image out;
  out.width = w;
  out.height = h;
  out.rgba8.assign(size_t(w) * size_t(h) * 4, 255);
  for (int y = 0; y < h; ++y) {
    std::array<float, 3> right{0.0f, 0.0f, 0.0f};
    const size_t row = size_t(h - 1 - y) * size_t(w);
    for (int x = 0; x < w; ++x) {
      std::array<float, 3> e{};
      for (size_t c = 0; c < 3; ++c) {
        float v = float(in.rgba8[(row + size_t(x)) * 4 + c]) / 255.0f + right[c];
        if (y > 0) {
          const size_t prev = size_t((y - 1) & 1) * size_t(w);
          if (x + 1 < w) v += below[prev + size_t(x) + 1][c] * (3.0f / 16.0f);
          v += below[prev + size_t(x)][c] * (5.0f / 16.0f);
          if (x > 0) v += below[prev + size_t(x) - 1][c] * (1.0f / 16.0f);
        }
        const float q = std::clamp(std::floor(std::clamp(v, 0.0f, 1.0f) * steps + 0.5f), 0.0f, steps) / steps;
        e[c] = v - q;
        right[c] = e[c] * (7.0f / 16.0f);
        out.rgba8[(row + size_t(x)) * 4 + c] = uint8_t(std::lround(q * 255.0f));
      }
      below[size_t(y & 1) * size_t(w) + size_t(x)] = e;
    }
  }
  return out;
}

// The anisotropic Kuwahara filter (three steps: structure tensor, its
// smoothing and eigenvectors, the eight-sector filter) on `in`.
inline Image kuwaharaReference(const Image& in, double radius, double q) {
  using namespace stylised_detail;
  const Source8 src{in};
  const int w = in.width, h = in.height;
  const size_t n = size_t(w) * size_t(h);
  std::vector<std::array<double, 3>> tensor(n);  // E, G, F; y up
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double e = 0, g = 0, f = 0;
      for (int ch = 0; ch < 3; ++ch) {
        auto c = [&](int dx, int dy) { return src.fetch(x + dx, y + dy)[size_t(ch)]; };
        const double gx = ((c(1, 1) + 2 * c(1, 0) + c(1, -1)) - (c(-1, 1) + 2 * c(-1, 0) + c(-1, -1))) * 0.25;
        const double gy = ((c(-1, 1) + 2 * c(0, 1) + c(1, 1)) - (c(-1, -1) + 2 * c(0, -1) + c(1, -1))) * 0.25;
        e += gx * gx, g += gy * gy, f += gx * gy;
      }
      tensor[size_t(y) * size_t(w) + size_t(x)] = {e, g, f};
    }
  auto tensorAt = [&](int x, int y) {
    return tensor[size_t(std::clamp(y, 0, h - 1)) * size_t(w) + size_t(std::clamp(x, 0, w - 1))];
  };
  struct Orientation {
    double tx, ty, a;
  };
  std::vector<Orientation> orient(n);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::array<double, 3> sum{};
      double weights = 0;
      for (int j = -3; j <= 3; ++j)
        for (int i = -3; i <= 3; ++i) {
          const double wgt = std::exp(-double(i * i + j * j) / (2.0 * 1.5 * 1.5));
          for (size_t k = 0; k < 3; ++k) sum[k] += wgt * tensorAt(x + i, y + j)[k];
          weights += wgt;
        }
      const double e = sum[0] / weights, g = sum[1] / weights, f = sum[2] / weights;
      const double root = std::sqrt((e - g) * (e - g) + 4 * f * f);
      const double l1 = 0.5 * (e + g + root), l2 = 0.5 * (e + g - root);
      double tx = l1 - e, ty = -f;
      const double len = std::hypot(tx, ty);
      if (len * len > 1e-12) tx /= len, ty /= len;
      else tx = 0, ty = 1;
      orient[size_t(y) * size_t(w) + size_t(x)] = {tx, ty, l1 + l2 > 1e-8 ? (l1 - l2) / (l1 + l2) : 0.0};
    }
  Image out;
  out.width = w;
  out.height = h;
  out.rgba8.assign(n * 4, 255);
  const double zeta = 2.0 / std::max(radius, 1.0), zeroCross = 0.58;
  const double eta = (zeta + std::cos(zeroCross)) / (std::sin(zeroCross) * std::sin(zeroCross));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Orientation& o = orient[size_t(y) * size_t(w) + size_t(x)];
      const double a = radius * std::clamp(1.0 + o.a, 0.1, 2.0), b = radius * std::clamp(1.0 / (1.0 + o.a), 0.1, 2.0);
      const double cp = o.tx, sp = o.ty;
      const int maxX = int(std::sqrt(a * a * cp * cp + b * b * sp * sp));
      const int maxY = int(std::sqrt(a * a * sp * sp + b * b * cp * cp));
      std::array<std::array<double, 4>, 8> m{};
      std::array<std::array<double, 3>, 8> s{};
      for (int j = -maxY; j <= maxY; ++j)
        for (int i = -maxX; i <= maxX; ++i) {
          // Rotated by -phi into the ellipse's frame, scaled to 0.5 at its edge.
          double vx = (cp * i + sp * j) * 0.5 / a, vy = (-sp * i + cp * j) * 0.5 / b;
          if (vx * vx + vy * vy > 0.25) continue;
          const Rgb c = src.fetch(x + i, y + j);
          std::array<double, 8> wk{};
          double sum = 0;
          auto sector = [&](int k, double z) { wk[size_t(k)] = std::max(0.0, z) * std::max(0.0, z), sum += wk[size_t(k)]; };
          double vxx = zeta - eta * vx * vx, vyy = zeta - eta * vy * vy;
          sector(0, vy + vxx), sector(2, -vx + vyy), sector(4, -vy + vxx), sector(6, vx + vyy);
          const double rx = 0.70710678 * (vx - vy), ry = 0.70710678 * (vx + vy);
          vx = rx, vy = ry;
          vxx = zeta - eta * vx * vx, vyy = zeta - eta * vy * vy;
          sector(1, vy + vxx), sector(3, -vx + vyy), sector(5, -vy + vxx), sector(7, vx + vyy);
          if (sum <= 0) continue;
          const double g = std::exp(-3.125 * (vx * vx + vy * vy)) / sum;
          for (size_t k = 0; k < 8; ++k) {
            const double wgt = wk[k] * g;
            for (size_t ch = 0; ch < 3; ++ch) m[k][ch] += c[ch] * wgt, s[k][ch] += c[ch] * c[ch] * wgt;
            m[k][3] += wgt;
          }
        }
      Rgb result{};
      double total = 0;
      for (size_t k = 0; k < 8; ++k) {
        if (m[k][3] <= 0) continue;
        double var = 0;
        Rgb mean{};
        for (size_t ch = 0; ch < 3; ++ch) {
          mean[ch] = m[k][ch] / m[k][3];
          var += std::abs(s[k][ch] / m[k][3] - mean[ch] * mean[ch]);
        }
        const double wgt = 1.0 / (1.0 + std::pow(255.0 * var, 0.5 * q));
        for (size_t ch = 0; ch < 3; ++ch) result[ch] += mean[ch] * wgt;
        total += wgt;
      }
      if (total > 0) for (double& v : result) v /= total;
      else result = src.fetch(x, y);
      uint8_t* p = &out.rgba8[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
      for (size_t i = 0; i < 3; ++i) p[i] = uint8_t(std::lround(std::clamp(result[i], 0.0, 1.0) * 255.0));
    }
  return out;
}

}  // namespace hs::test
