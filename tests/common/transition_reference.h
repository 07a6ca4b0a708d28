#pragma once
// The stylised transitions (sequencer::Transition, shaders/group_combine.frag)
// written again on the CPU, from their description in docs/sequencer.md
// "Transitions", in double precision: the reference the renderer's
// combined image is held against. Images are linear RGBA floats with rows
// top-down (Renderer::readHdr); the patterns are defined with y up, as
// gl_FragCoord is.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "particles/rng.h"
#include "sequencer/camera_cuts.h"

namespace hs::test {

namespace transition_detail {

// The shader's hash is the particles' (lowbias32): the same bits.
inline double rand3(uint32_t a, uint32_t b, uint32_t c) {
  using particles::hashU32;
  return double(hashU32(a ^ hashU32(b ^ hashU32(c))) >> 8) / 16777216.0;
}

struct Rgba {
  double v[4] = {0, 0, 0, 0};
  Rgba& operator+=(const Rgba& o) {
    for (int i = 0; i < 4; ++i) v[i] += o.v[i];
    return *this;
  }
};
inline Rgba mix(const Rgba& a, const Rgba& b, double t) {
  Rgba o;
  for (int i = 0; i < 4; ++i) o.v[i] = a.v[i] * (1.0 - t) + b.v[i] * t;
  return o;
}
inline double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// One image with y up and clamped reads.
struct Source {
  const Image& img;
  Rgba fetch(int x, int y) const {
    x = std::clamp(x, 0, img.width - 1);
    y = std::clamp(y, 0, img.height - 1);
    const float* p = &img.rgbaF[(size_t(img.height - 1 - y) * size_t(img.width) + size_t(x)) * 4];
    return {{p[0], p[1], p[2], p[3]}};
  }
  // Bilinear at a position in pixels (centres at +0.5), clamp to edge.
  Rgba sample(double px, double py) const {
    const double fx = px - 0.5, fy = py - 0.5;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const double tx = fx - x0, ty = fy - y0;
    return mix(mix(fetch(x0, y0), fetch(x0 + 1, y0), tx), mix(fetch(x0, y0 + 1), fetch(x0 + 1, y0 + 1), tx), ty);
  }
};

inline double edge(double x, double p, double soft) {
  const double e = p * (1.0 + 2.0 * soft) - soft;
  return 1.0 - smoothstep(e - soft, e + soft, x);
}

}  // namespace transition_detail

// `from` (outgoing) into `to` (incoming) by patterned transition `t` at
// eased progress `p`, frame `frame` (the glitch's seed).
inline Image transitionReference(const Image& from, const Image& to, sequencer::Transition t, double p, int64_t frame) {
  using namespace transition_detail;
  using T = sequencer::Transition;
  const Source a{from}, b{to};
  const int w = from.width, h = from.height;
  Image out;
  out.width = w;
  out.height = h;
  out.rgbaF.assign(size_t(w) * size_t(h) * 4, 0.0f);
  const double lines = h / 1080.0;
  const double peak = std::sin(M_PI * p);
  const uint32_t seed = uint32_t(uint64_t(frame));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double qx = (px - 0.5 * w) / h, qy = (py - 0.5 * h) / h;
      Rgba c;
      switch (t) {
        case T::CrossfadeBlur: {
          const double radius = peak * 16.0 * lines;
          Rgba sa, sb;
          for (int i = 0; i < 16; ++i) {
            const double rho = radius * std::sqrt((i + 0.5) / 16.0), th = i * 2.39996323;
            sa += a.sample(px + rho * std::cos(th), py + rho * std::sin(th));
            sb += b.sample(px + rho * std::cos(th), py + rho * std::sin(th));
          }
          c = mix(sa, sb, p);
          for (double& v : c.v) v /= 16.0;
          break;
        }
        case T::Swipe: c = mix(a.fetch(x, y), b.fetch(x, y), edge(px / w, p, 0.03)); break;
        case T::RadialWipe: {
          double turn = std::atan2(qx, qy) / (2.0 * M_PI);
          if (turn < 0.0) turn += 1.0;
          c = mix(a.fetch(x, y), b.fetch(x, y), edge(turn, p, 0.01));
          break;
        }
        case T::WaterDrop: {
          const double d = std::hypot(qx, qy);
          const double reach = p * (0.5 * std::hypot(double(w), double(h)) / h + 0.04);
          const double ahead = d - reach;
          const double dx = d > 1e-6 ? qx / d : 0.0, dy = d > 1e-6 ? qy / d : 0.0;
          const double amp = 0.015 * (1.0 - p) * std::exp(-ahead * ahead / 0.004);
          const double off = amp * std::sin(ahead * 90.0) * h;
          c = mix(a.sample(px + dx * off, py + dy * off), b.fetch(x, y), 1.0 - smoothstep(-0.02, 0.02, ahead));
          break;
        }
        case T::PixelDissolve: {
          const int block = std::max(1, int(std::floor(24.0 * lines * peak + 0.5)));
          const int cx = x / block, cy = y / block;
          const int sx = cx * block + block / 2, sy = cy * block + block / 2;
          c = rand3(uint32_t(cx), uint32_t(cy), uint32_t(block)) < p ? b.fetch(sx, sy) : a.fetch(sx, sy);
          break;
        }
        case T::Glitch: {
          const int band = std::max(2, int(std::floor(12.0 * lines + 0.5)));
          const uint32_t k = uint32_t(y / band);
          const bool displaced = rand3(k, seed, 1u) < 0.6 * peak;
          const int shift = displaced ? int(std::floor((rand3(k, seed, 2u) - 0.5) * 0.2 * w * peak + 0.5)) : 0;
          const int split = int(std::floor(6.0 * lines * peak + 0.5));
          const Source& s = rand3(k, seed, 3u) < p ? b : a;
          const int sx = x + shift;
          const Rgba g = s.fetch(sx, y);
          c = {{s.fetch(sx + split, y).v[0], g.v[1], s.fetch(sx - split, y).v[2], g.v[3]}};
          break;
        }
        case T::ZoomBlur: {
          const double z = 0.25 * peak;
          Rgba sa, sb;
          for (int i = 0; i < 16; ++i) {
            const double k = 1.0 - z * i / 15.0;
            const double tx = 0.5 * w + (px - 0.5 * w) * k, ty = 0.5 * h + (py - 0.5 * h) * k;
            sa += a.sample(tx, ty);
            sb += b.sample(tx, ty);
          }
          c = mix(sa, sb, smoothstep(0.25, 0.75, p));
          for (double& v : c.v) v /= 16.0;
          break;
        }
        default: c = mix(a.fetch(x, y), b.fetch(x, y), p); break;
      }
      float* o = &out.rgbaF[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
      for (int i = 0; i < 4; ++i) o[i] = float(c.v[i]);
    }
  }
  return out;
}

}  // namespace hs::test
