#include "particles/sprites.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/vec3.hpp>

#include "core/srgb.h"
#include "particles/noise.h"
#include "particles/rng.h"

namespace hs::particles {

namespace {

constexpr double kPi = std::numbers::pi;

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Distance from p to the segment a-b (2D).
double segmentDistance(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double l2 = dx * dx + dy * dy;
  const double t = l2 > 0.0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / l2, 0.0, 1.0) : 0.0;
  const double qx = ax + t * dx - px, qy = ay + t * dy - py;
  return std::sqrt(qx * qx + qy * qy);
}

void put(Image& img, int x, int y, double r, double g, double b, double a) {
  uint8_t* p = &img.rgba8[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  p[0] = linearToSrgb8(float(r));
  p[1] = linearToSrgb8(float(g));
  p[2] = linearToSrgb8(float(b));
  p[3] = uint8_t(std::lround(std::clamp(a, 0.0, 1.0) * 255.0));
}

// Fractal gradient noise, about [-1, 1].
double fbm(glm::dvec3 p, uint32_t seed, int octaves) {
  double sum = 0.0, amp = 0.5;
  for (int o = 0; o < octaves; ++o) {
    sum += amp * gradientNoise(p, seed + uint32_t(o) * 101u).value;
    p *= 2.03;
    amp *= 0.5;
  }
  return sum;
}

}  // namespace

Image snowflakeSprite(int size, uint32_t seed) {
  size = std::max(size, 4);
  Image img = Image::make8(size, size);
  auto rnd = [&](uint32_t i) { return unitFromHash(hashKey(seed, 0x5f1a, i, 0)); };
  // One arm along +x in [0, 1] (units of the flake's radius), with side branches.
  struct Seg {
    double ax, ay, bx, by, w;
  };
  std::vector<Seg> arm{{0.0, 0.0, 0.92, 0.0, 0.045}};
  const int branches = 2 + int(rnd(0) * 3.0);
  for (int b = 0; b < branches; ++b) {
    const double at = 0.25 + 0.6 * (double(b) + rnd(10 + uint32_t(b))) / double(branches);
    const double len = (0.15 + 0.3 * rnd(20 + uint32_t(b))) * (1.1 - at);
    const double ang = (35.0 + 30.0 * rnd(30 + uint32_t(b))) * kPi / 180.0;
    arm.push_back({at, 0.0, at + len * std::cos(ang), len * std::sin(ang), 0.03});
  }
  const double hub = 0.08 + 0.1 * rnd(40);
  const double half = 0.5 * double(size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // 2x2 supersampling of coverage.
      double cover = 0.0;
      for (int s = 0; s < 4; ++s) {
        const double px = ((x + 0.25 + 0.5 * (s & 1)) - half) / (half * 0.95);
        const double py = ((y + 0.25 + 0.5 * (s >> 1)) - half) / (half * 0.95);
        // Fold into the first 1/12 wedge (six arms, mirrored).
        const double r = std::sqrt(px * px + py * py);
        double a = std::atan2(py, px);
        a = std::fmod(a + 2.0 * kPi, kPi / 3.0);
        if (a > kPi / 6.0) a = kPi / 3.0 - a;
        const double fx = r * std::cos(a), fy = r * std::sin(a);
        double d = r - hub;
        for (const Seg& g : arm) d = std::min(d, segmentDistance(fx, fy, g.ax, g.ay, g.bx, g.by) - g.w);
        cover += d < 0.0 ? 1.0 : 0.0;
      }
      put(img, x, y, 1.0, 1.0, 1.0, cover / 4.0);
    }
  return img;
}

Image smokePuffSprite(int size, uint32_t seed) {
  size = std::max(size, 4);
  Image img = Image::make8(size, size);
  const double half = 0.5 * double(size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double px = (x + 0.5 - half) / half, py = (y + 0.5 - half) / half;
      const double r = std::sqrt(px * px + py * py);
      const double n = fbm({px * 2.5, py * 2.5, 0.37}, seed, 5);
      const double falloff = 1.0 - smoothstep(0.35, 1.0, r + 0.25 * n);
      const double density = std::clamp(falloff * (0.75 + 0.5 * n), 0.0, 1.0);
      put(img, x, y, 1.0, 1.0, 1.0, density);
    }
  return img;
}

Flipbook flameFlipbook(int frameSize, int frames, uint32_t seed) {
  Flipbook f;
  f.frameSize = frameSize = std::max(frameSize, 4);
  f.frames = frames = std::max(frames, 1);
  f.columns = int(std::ceil(std::sqrt(double(frames))));
  f.rows = (frames + f.columns - 1) / f.columns;
  f.atlas = Image::make8(f.columns * frameSize, f.rows * frameSize);
  for (int fr = 0; fr < frames; ++fr) {
    const int ox = (fr % f.columns) * frameSize, oy = (fr / f.columns) * frameSize;
    // Loops: the noise is sampled on a circle in its third dimension.
    const double phase = 2.0 * kPi * double(fr) / double(frames);
    const double cz = 0.6 * std::cos(phase), cw = 0.6 * std::sin(phase);
    for (int y = 0; y < frameSize; ++y)
      for (int x = 0; x < frameSize; ++x) {
        const double u = (x + 0.5) / frameSize * 2.0 - 1.0;  // -1..1 across
        const double v = 1.0 - (y + 0.5) / frameSize;        // 0 at the bottom, 1 at the top
        const double n = fbm({u * 3.0, v * 3.0 - 2.0 * double(fr) / double(frames) + cw, cz}, seed, 4);
        // A teardrop: wide at the base, narrowing to the tip, its edge torn by the noise.
        const double width = 0.55 * std::pow(std::max(0.0, 1.0 - v), 0.7) * (1.0 - std::exp(-v * 12.0)) + 0.02;
        const double edge = std::abs(u + 0.15 * n * v) / width;
        // 1 on the axis near the base, falling to 0 at the torn edge and towards the tip.
        const double radial = 1.0 - smoothstep(0.0, 1.0, edge + 0.35 * n);
        const double vertical = 1.0 - smoothstep(0.35, 1.0, v + 0.2 * n);
        const double intensity = std::clamp(radial * vertical, 0.0, 1.0);
        // Black body-ish ramp (linear): deep red at the edge, orange, yellow, near white in the core.
        const double r = std::clamp(intensity * 1.8, 0.0, 1.0);
        const double g = std::clamp(intensity * intensity * 1.2 - 0.1, 0.0, 1.0);
        const double b = std::clamp(std::pow(intensity, 4.0) - 0.3, 0.0, 1.0);
        const double alpha = smoothstep(0.0, 0.3, intensity);
        put(f.atlas, ox + x, oy + y, r, g, b, alpha);
      }
  }
  return f;
}

}  // namespace hs::particles
