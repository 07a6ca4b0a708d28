#include "terrain/nodata_fill.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "terrain/gdal_door.h"

namespace hs::terrain {

const char* nodataFillName(NodataFill f) {
  return f == NodataFill::InverseDistance ? "inverse-distance (GDALFillNodata) + diffusion" : "diffusion (harmonic)";
}

namespace {

void countVoids(const std::vector<uint8_t>& valid, int w, int h, FillReport& r) {
  std::vector<uint8_t> seen(valid.size(), 0);
  std::deque<size_t> queue;
  for (size_t start = 0; start < valid.size(); ++start) {
    if (valid[start] || seen[start]) continue;
    ++r.voids;
    size_t size = 0;
    seen[start] = 1;
    queue.push_back(start);
    while (!queue.empty()) {
      const size_t i = queue.front();
      queue.pop_front();
      ++size;
      const int x = int(i % size_t(w)), y = int(i / size_t(w));
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
        const size_t j = size_t(ny[k]) * size_t(w) + size_t(nx[k]);
        if (!valid[j] && !seen[j]) {
          seen[j] = 1;
          queue.push_back(j);
        }
      }
    }
    r.largestVoid = std::max(r.largestVoid, size);
  }
}

struct Level {
  int w = 0, h = 0;
  std::vector<double> v;
  std::vector<uint8_t> ok;
};

// Red-black Gauss-Seidel on the samples that were nodata: each becomes the
// mean of its in-grid 4-neighbours. Valid samples stay fixed.
void relax(Level& l, int iterations) {
  std::vector<size_t> holes;
  for (size_t i = 0; i < l.ok.size(); ++i)
    if (!l.ok[i]) holes.push_back(i);
  if (holes.empty()) return;
  for (int it = 0; it < iterations; ++it)
    for (int colour = 0; colour < 2; ++colour)
      for (size_t i : holes) {
        const int x = int(i % size_t(l.w)), y = int(i / size_t(l.w));
        if (((x + y) & 1) != colour) continue;
        double s = 0.0;
        int n = 0;
        if (x > 0) { s += l.v[i - 1]; ++n; }
        if (x + 1 < l.w) { s += l.v[i + 1]; ++n; }
        if (y > 0) { s += l.v[i - size_t(l.w)]; ++n; }
        if (y + 1 < l.h) { s += l.v[i + size_t(l.w)]; ++n; }
        if (n) l.v[i] = s / n;
      }
}

void diffusionFill(std::vector<float>& values, const std::vector<uint8_t>& valid, int w, int h) {
  std::vector<Level> pyr(1);
  pyr[0].w = w;
  pyr[0].h = h;
  pyr[0].v.assign(values.begin(), values.end());
  pyr[0].ok = valid;
  while (pyr.back().w > 2 || pyr.back().h > 2) {
    const Level& f = pyr.back();
    Level c;
    c.w = (f.w + 1) / 2;
    c.h = (f.h + 1) / 2;
    c.v.assign(size_t(c.w) * size_t(c.h), 0.0);
    c.ok.assign(c.v.size(), 0);
    for (int y = 0; y < c.h; ++y)
      for (int x = 0; x < c.w; ++x) {
        double s = 0.0;
        int n = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int fx = 2 * x + dx, fy = 2 * y + dy;
            if (fx >= f.w || fy >= f.h) continue;
            const size_t j = size_t(fy) * size_t(f.w) + size_t(fx);
            if (f.ok[j]) { s += f.v[j]; ++n; }
          }
        if (n) {
          c.v[size_t(y) * size_t(c.w) + size_t(x)] = s / n;
          c.ok[size_t(y) * size_t(c.w) + size_t(x)] = 1;
        }
      }
    pyr.push_back(std::move(c));
  }
  // Coarsest: nodata samples take the mean of the valid ones, then relax.
  {
    Level& top = pyr.back();
    double s = 0.0;
    int n = 0;
    for (size_t i = 0; i < top.v.size(); ++i)
      if (top.ok[i]) { s += top.v[i]; ++n; }
    for (size_t i = 0; i < top.v.size(); ++i)
      if (!top.ok[i]) top.v[i] = n ? s / n : 0.0;
    relax(top, 50);
  }
  for (int lv = int(pyr.size()) - 2; lv >= 0; --lv) {
    Level& f = pyr[size_t(lv)];
    const Level& c = pyr[size_t(lv) + 1];
    // Start each nodata sample from the coarser level, bilinear (cell centres).
    for (int y = 0; y < f.h; ++y)
      for (int x = 0; x < f.w; ++x) {
        const size_t i = size_t(y) * size_t(f.w) + size_t(x);
        if (f.ok[i]) continue;
        const double cx = std::clamp((x + 0.5) / 2.0 - 0.5, 0.0, double(c.w - 1));
        const double cy = std::clamp((y + 0.5) / 2.0 - 0.5, 0.0, double(c.h - 1));
        const int x0 = std::min(int(cx), c.w - 1), y0 = std::min(int(cy), c.h - 1);
        const int x1 = std::min(x0 + 1, c.w - 1), y1 = std::min(y0 + 1, c.h - 1);
        const double tx = cx - x0, ty = cy - y0;
        auto cv = [&](int xx, int yy) { return c.v[size_t(yy) * size_t(c.w) + size_t(xx)]; };
        f.v[i] = (cv(x0, y0) * (1 - tx) + cv(x1, y0) * tx) * (1 - ty) + (cv(x0, y1) * (1 - tx) + cv(x1, y1) * tx) * ty;
      }
    relax(f, lv == 0 ? 60 : 30);
  }
  for (size_t i = 0; i < values.size(); ++i)
    if (!valid[i]) values[i] = float(pyr[0].v[i]);
}

}  // namespace

bool fillNodata(std::vector<float>& values, const std::vector<uint8_t>& validIn, int w, int h, NodataFill method,
                double idwMaxDistance, FillReport& r, const Progress* progress) {
  r = FillReport{};
  r.method = nodataFillName(method);
  std::vector<uint8_t> valid = validIn;
  const size_t good = size_t(std::count(valid.begin(), valid.end(), uint8_t(1)));
  if (good == 0) return false;
  r.filled = valid.size() - good;
  if (r.filled == 0) return true;
  countVoids(valid, w, h, r);

  if (method == NodataFill::InverseDistance) {
    std::string missing;
    if (const gdal_door::Backend* gdal = gdal_door::backend(missing))
      gdal->fillInverseDistance(values, valid, w, h, idwMaxDistance > 0.0 ? idwMaxDistance : 100.0, progress);
    else
      r.method = "diffusion (harmonic; inverse distance needs GDAL: " + missing + ")";
  }
  // Whatever is left (all of it for Diffusion) by harmonic interpolation.
  r.byDiffusion = valid.size() - size_t(std::count(valid.begin(), valid.end(), uint8_t(1)));
  if (r.byDiffusion) diffusionFill(values, valid, w, h);
  return true;
}

}  // namespace hs::terrain
