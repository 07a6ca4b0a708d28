#include "terrain/grid_resample.h"

#include <algorithm>
#include <cmath>

namespace hs::terrain {

const char* resamplingName(Resampling r) {
  switch (r) {
    case Resampling::Nearest: return "nearest";
    case Resampling::Bilinear: return "bilinear";
    case Resampling::Cubic: return "cubic";
  }
  return "?";
}

namespace {

double catmullRom(double p0, double p1, double p2, double p3, double t) {
  return p1 + 0.5 * t * (p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
}

}  // namespace

std::vector<float> resampleGrid(const std::vector<float>& src, int w, int h, int outW, int outH, Resampling m) {
  std::vector<float> out(size_t(outW) * size_t(outH));
  if (w == outW && h == outH) return src;
  auto at = [&](int x, int y) {
    return double(src[size_t(std::clamp(y, 0, h - 1)) * size_t(w) + size_t(std::clamp(x, 0, w - 1))]);
  };
  const double sx = outW > 1 ? double(w - 1) / double(outW - 1) : 0.0;
  const double sy = outH > 1 ? double(h - 1) / double(outH - 1) : 0.0;
  for (int y = 0; y < outH; ++y) {
    const double fy = y * sy;
    const int iy = std::min(int(fy), h - 1);
    const double ty = fy - iy;
    for (int x = 0; x < outW; ++x) {
      const double fx = x * sx;
      const int ix = std::min(int(fx), w - 1);
      const double tx = fx - ix;
      double v;
      switch (m) {
        case Resampling::Nearest: v = at(int(std::lround(fx)), int(std::lround(fy))); break;
        case Resampling::Cubic: {
          double col[4];
          for (int k = 0; k < 4; ++k)
            col[k] = catmullRom(at(ix - 1, iy - 1 + k), at(ix, iy - 1 + k), at(ix + 1, iy - 1 + k), at(ix + 2, iy - 1 + k), tx);
          v = catmullRom(col[0], col[1], col[2], col[3], ty);
          break;
        }
        case Resampling::Bilinear:
        default:
          v = (at(ix, iy) * (1 - tx) + at(ix + 1, iy) * tx) * (1 - ty) + (at(ix, iy + 1) * (1 - tx) + at(ix + 1, iy + 1) * tx) * ty;
      }
      out[size_t(y) * size_t(outW) + size_t(x)] = float(v);
    }
  }
  return out;
}

}  // namespace hs::terrain
