#pragma once
// The CPU twin of the renderer's weighted Voronoi stippling
// (render/passes/stipple_passes.h, shaders/stipple*.{frag,comp}) for
// test_stipple: the same grid, candidates, integer sums and dots, with the
// Voronoi cells found exactly (nearest site by a bucketed search, ties to
// the lower index) instead of by jump flooding. Images are top row first;
// the shaders' rows grow upwards, so grid row y covers image rows
// height - 1 - 2y and height - 2 - 2y.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/image.h"
#include "core/lowbias32.h"
#include "core/stipple_layout.h"

namespace hs::test {

struct StippleTwin {
  int gridWidth = 1, gridHeight = 1;
  float spacingCells = 1.5f, radiusPx = 1.0f;
  std::vector<uint8_t> darkness;  // per cell, 0..255, y upwards
  std::vector<float> x, y;        // per slot; x < 0: no dot
  std::vector<uint32_t> owner;    // per cell, the nearest site (UINT32_MAX: none)
  // The mean distance, in cells, from each site to the darkness-weighted
  // centroid of its cell (how far from a centroidal Voronoi tessellation),
  // weighted by the cell's darkness.
  double centroidGap = 0.0;
};

namespace stipple_detail {

inline float radicalInverse(uint32_t i, uint32_t base) {
  const float inv = 1.0f / float(base);
  float f = inv, r = 0.0f;
  while (i > 0) {
    r += f * float(i % base);
    i /= base;
    f *= inv;
  }
  return r;
}

// The exact cells: each cell's nearest live site (ties: the lower index),
// found through buckets of sites searched in growing rings.
inline void assignCells(StippleTwin& t) {
  const int gw = t.gridWidth, gh = t.gridHeight;
  const int bucket = std::max(2, int(std::ceil(t.spacingCells * 2.0f)));
  const int bw = (gw + bucket - 1) / bucket, bh = (gh + bucket - 1) / bucket;
  std::vector<std::vector<uint32_t>> buckets(size_t(bw) * size_t(bh));
  // A site sharing its cell with a lower-indexed one has no cell (the
  // renderer's seeds: the lower index wins the cell, the other is never seen).
  std::vector<uint32_t> seedOf(size_t(gw) * size_t(gh), UINT32_MAX);
  for (uint32_t s = 0; s < t.x.size(); ++s) {
    if (t.x[s] < 0.0f) continue;
    const int cx = std::clamp(int(t.x[s]), 0, gw - 1), cy = std::clamp(int(t.y[s]), 0, gh - 1);
    uint32_t& seed = seedOf[size_t(cy) * size_t(gw) + size_t(cx)];
    if (seed != UINT32_MAX) continue;  // ascending order: the first is the lowest
    seed = s;
    buckets[size_t(cy / bucket) * size_t(bw) + size_t(cx / bucket)].push_back(s);
  }
  t.owner.assign(size_t(gw) * size_t(gh), UINT32_MAX);
  for (int cy = 0; cy < gh; ++cy)
    for (int cx = 0; cx < gw; ++cx) {
      const float px = float(cx) + 0.5f, py = float(cy) + 0.5f;
      const int bx = cx / bucket, by = cy / bucket;
      uint32_t best = UINT32_MAX;
      float bestD = std::numeric_limits<float>::max();
      for (int ring = 0; ring <= std::max(bw, bh); ++ring) {
        // Every site in ring r is at least (r - 1) buckets away.
        const float near = float(std::max(0, ring - 1) * bucket);
        if (best != UINT32_MAX && near * near > bestD) break;
        for (int y = by - ring; y <= by + ring; ++y)
          for (int x = bx - ring; x <= bx + ring; ++x) {
            if (std::max(std::abs(x - bx), std::abs(y - by)) != ring || x < 0 || y < 0 || x >= bw || y >= bh) continue;
            for (uint32_t s : buckets[size_t(y) * size_t(bw) + size_t(x)]) {
              const float dx = t.x[s] - px, dy = t.y[s] - py;
              const float d = dx * dx + dy * dy;
              if (d < bestD || (d == bestD && s < best)) best = s, bestD = d;
            }
          }
      }
      t.owner[size_t(cy) * size_t(gw) + size_t(cx)] = best;
    }
}

}  // namespace stipple_detail

// `image`: the picture before stippling; the layout the renderer takes for
// its size (core/stipple_layout.h).
inline StippleTwin stippleTwin(const Image& image, const StippleLayout& layout, int iterations) {
  using namespace stipple_detail;
  StippleTwin t;
  const int w = image.width, h = image.height;
  t.gridWidth = layout.gridWidth;
  t.gridHeight = layout.gridHeight;
  t.spacingCells = layout.spacingCells;
  t.radiusPx = layout.radiusPx;
  const uint32_t candidates = layout.candidates;
  const int gw = t.gridWidth, gh = t.gridHeight;
  t.darkness.resize(size_t(gw) * size_t(gh));
  for (int cy = 0; cy < gh; ++cy)
    for (int cx = 0; cx < gw; ++cx) {
      float sum = 0.0f;
      int n = 0;
      for (int y = 2 * cy; y < std::min(h, 2 * cy + 2); ++y)
        for (int x = 2 * cx; x < std::min(w, 2 * cx + 2); ++x) {
          const uint8_t* p = &image.rgba8[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
          sum += 0.2126f * (float(p[0]) / 255.0f) + 0.7152f * (float(p[1]) / 255.0f) + 0.0722f * (float(p[2]) / 255.0f);
          ++n;
        }
      const float dark = std::clamp(1.0f - sum / float(std::max(n, 1)), 0.0f, 1.0f);
      t.darkness[size_t(cy) * size_t(gw) + size_t(cx)] = uint8_t(std::lround(dark * 255.0f));
    }
  t.x.resize(candidates);
  t.y.resize(candidates);
  for (uint32_t i = 0; i < candidates; ++i) {
    const float px = radicalInverse(i + 1, 2) * float(gw), py = radicalInverse(i + 1, 3) * float(gh);
    const int cx = std::min(int(px), gw - 1), cy = std::min(int(py), gh - 1);
    const bool kept = t.darkness[size_t(cy) * size_t(gw) + size_t(cx)] > lowbias32(i) % 255u;
    t.x[i] = kept ? px : -1.0f;
    t.y[i] = kept ? py : -1.0f;
  }
  // Lloyd steps: the cells, their darkness-weighted centroids (integer sums
  // as the renderer's), each site moved there; the last cells kept.
  std::vector<uint64_t> sw(candidates), sx(candidates), sy(candidates);
  for (int it = 0;; ++it) {
    assignCells(t);
    std::fill(sw.begin(), sw.end(), 0);
    std::fill(sx.begin(), sx.end(), 0);
    std::fill(sy.begin(), sy.end(), 0);
    for (int cy = 0; cy < gh; ++cy)
      for (int cx = 0; cx < gw; ++cx) {
        const size_t c = size_t(cy) * size_t(gw) + size_t(cx);
        const uint32_t s = t.owner[c], wgt = t.darkness[c];
        if (s == UINT32_MAX || wgt == 0) continue;
        sw[s] += wgt;
        sx[s] += uint64_t(wgt) * uint64_t(2 * cx + 1);
        sy[s] += uint64_t(wgt) * uint64_t(2 * cy + 1);
      }
    auto centroid = [&](uint32_t s, float* cx, float* cy) {
      const float sxf = float(uint32_t(sx[s] >> 32)) * 4294967296.0f + float(uint32_t(sx[s]));
      const float syf = float(uint32_t(sy[s] >> 32)) * 4294967296.0f + float(uint32_t(sy[s]));
      *cx = sxf / (2.0f * float(sw[s]));
      *cy = syf / (2.0f * float(sw[s]));
    };
    if (it == iterations) {
      double gap = 0.0, weight = 0.0;
      for (uint32_t s = 0; s < candidates; ++s) {
        if (t.x[s] < 0.0f || sw[s] == 0) continue;
        float cx, cy;
        centroid(s, &cx, &cy);
        gap += double(sw[s]) * std::hypot(double(cx - t.x[s]), double(cy - t.y[s]));
        weight += double(sw[s]);
      }
      t.centroidGap = weight > 0.0 ? gap / weight : 0.0;
      break;
    }
    for (uint32_t s = 0; s < candidates; ++s)
      if (t.x[s] >= 0.0f && sw[s] > 0) centroid(s, &t.x[s], &t.y[s]);
  }
  return t;
}

// The dots drawn from the twin's final cells as the renderer draws them:
// black discs on white, each pixel's ink the largest coverage reaching it.
inline Image stippledPicture(const StippleTwin& t, int w, int h) {
  Image out = Image::make8(w, h);
  const float scaleX = float(w) / float(t.gridWidth), scaleY = float(h) / float(t.gridHeight);
  const int reach = int(std::ceil((t.radiusPx + 0.5f) / std::min(scaleX, scaleY)));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float px = float(x) + 0.5f, py = float(y) + 0.5f;
      const int cx = int(px / scaleX), cy = int(py / scaleY);
      float ink = 0.0f;
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const int nx = cx + dx, ny = cy + dy;
          if (nx < 0 || ny < 0 || nx >= t.gridWidth || ny >= t.gridHeight) continue;
          const uint32_t s = t.owner[size_t(ny) * size_t(t.gridWidth) + size_t(nx)];
          if (s == UINT32_MAX) continue;
          const float d = std::hypot(px - t.x[s] * scaleX, py - t.y[s] * scaleY);
          ink = std::max(ink, std::clamp(t.radiusPx + 0.5f - d, 0.0f, 1.0f));
        }
      uint8_t* p = &out.rgba8[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
      const uint8_t v = uint8_t(std::lround((1.0f - ink) * 255.0f));
      p[0] = p[1] = p[2] = v;
      p[3] = 255;
    }
  return out;
}

}  // namespace hs::test
