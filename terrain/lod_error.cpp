#include "terrain/lod_error.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/parallel.h"

namespace hs::terrain {
namespace {

// Heights of the window [x0, x0+w] x [y0, y0+h] (inclusive far edge), with
// samples beyond the grid reading as the nearest edge sample.
struct Window {
  int x0 = 0, y0 = 0, w = 0, h = 0;
  std::vector<float> v;  // (w+1) x (h+1)
  float at(int x, int y) const { return v[size_t(y - y0) * size_t(w + 1) + size_t(x - x0)]; }
};

void readWindow(const Heightfield& hf, int x0, int y0, int w, int h, Window& out) {
  out.x0 = x0;
  out.y0 = y0;
  out.w = w;
  out.h = h;
  out.v.resize(size_t(w + 1) * size_t(h + 1));
  const int nx = hf.samplesX(), ny = hf.samplesY();
  const Region inside = Region{x0, y0, x0 + w + 1, y0 + h + 1}.intersected(hf.bounds());
  const std::vector<float> block = hf.read(inside);
  for (int y = 0; y <= h; ++y) {
    const int sy = std::min(y0 + y, ny - 1) - inside.y0;
    const float* row = block.data() + size_t(sy) * size_t(inside.width());
    float* dst = out.v.data() + size_t(y) * size_t(w + 1);
    const int inW = std::min(x0 + w, nx - 1) - x0 + 1;  // samples of this row inside the grid
    std::copy(row, row + inW, dst);
    std::fill(dst + inW, dst + w + 1, row[inW - 1]);
  }
}

// Max |h - I_s| over the samples [bx, bx+bw) x [by, by+bh) of the window
// (inside the grid only), coarse spacing s; the window's origin is aligned
// to the coarse grid.
//
// Per band of s rows between two coarse rows, the coarse mesh along the
// band's bottom and top edges (A0, A1) and the cells' vertical differences
// at their right and left corners (D1, D0) are laid out per column first.
// Within a cell (split along (0,0)-(1,1), as the full-resolution mesh) the
// lower triangle (k >= dy) is A0 + fy D1 and the upper one A1 - (1 - fy) D0,
// so every row is one branch-free loop the compiler vectorises, whatever s
// (a loop per cell would spend more on set-up than on the 2 or 4 samples of
// a small level's cell).
[[gnu::noinline]] float blockError(const Window& win, int s, int bx, int by, int bw, int bh, int nx, int ny) {
  const int xEnd = std::min(bx + bw, nx), yEnd = std::min(by + bh, ny);
  const int w = xEnd - bx;
  if (w <= 0 || yEnd <= by) return 0.0f;
  const float inv = 1.0f / float(s);
  thread_local std::vector<float> A0, A1, D0, D1, K;
  A0.resize(size_t(w));
  A1.resize(size_t(w));
  D0.resize(size_t(w));
  D1.resize(size_t(w));
  K.resize(size_t(w));
  float worst = 0.0f;
  for (int cy = by; cy < yEnd; cy += s) {
    for (int cx = bx; cx < xEnd; cx += s) {
      const float h00 = win.at(cx, cy), h10 = win.at(cx + s, cy);
      const float h01 = win.at(cx, cy + s), h11 = win.at(cx + s, cy + s);
      const int n = std::min(s, xEnd - cx);
      for (int k = 0; k < n; ++k) {
        const size_t i = size_t(cx - bx + k);
        const float fx = float(k) * inv;
        A0[i] = h00 + fx * (h10 - h00);
        A1[i] = h01 + fx * (h11 - h01);
        D0[i] = h01 - h00;
        D1[i] = h11 - h10;
        K[i] = float(k);
      }
    }
    const int yb = std::min(cy + s, yEnd);
    for (int y = cy; y < yb; ++y) {
      const float dy = float(y - cy);
      const float fy = dy * inv, gy = 1.0f - fy;
      const float* __restrict row = win.v.data() + size_t(y - win.y0) * size_t(win.w + 1) + size_t(bx - win.x0);
      const float *__restrict a0 = A0.data(), *__restrict a1 = A1.data(), *__restrict d0 = D0.data(),
                  *__restrict d1 = D1.data(), *__restrict kk = K.data();
      // Four columns at a time with GCC/Clang vector extensions: the
      // auto-vectoriser leaves this select-and-max loop scalar.
      using v4 = float __attribute__((vector_size(16)));
      auto load = [](const float* p) {
        v4 v;
        std::memcpy(&v, p, sizeof v);
        return v;
      };
      const v4 vfy = {fy, fy, fy, fy}, vgy = {gy, gy, gy, gy}, vdy = {dy, dy, dy, dy}, zero = {0, 0, 0, 0};
      v4 vm = {worst, worst, worst, worst};
      int i = 0;
      for (; i + 4 <= w; i += 4) {
        const v4 lower = load(a0 + i) + vfy * load(d1 + i), upper = load(a1 + i) - vgy * load(d0 + i);
        const v4 d = load(row + i) - (load(kk + i) >= vdy ? lower : upper);
        const v4 a = d < zero ? -d : d;
        vm = a > vm ? a : vm;
      }
      float m = std::max(std::max(vm[0], vm[1]), std::max(vm[2], vm[3]));
      for (; i < w; ++i) {
        const float lower = a0[i] + fy * d1[i], upper = a1[i] - gy * d0[i];
        const float d = row[i] - (kk[i] >= dy ? lower : upper);
        m = std::max(m, std::abs(d));
      }
      worst = m;
    }
  }
  return worst;
}

}  // namespace

float lodErrorAt(const Heightfield& hf, int level, int x, int y) {
  if (level <= 0) return 0.0f;
  const int s = 1 << level;
  const int cx = (x / s) * s, cy = (y / s) * s;
  auto h = [&](int a, int b) { return hf.atClamped(a, b); };
  const float fx = float(x - cx) / float(s), fy = float(y - cy) / float(s);
  const float h00 = h(cx, cy), h10 = h(cx + s, cy), h01 = h(cx, cy + s), h11 = h(cx + s, cy + s);
  const float i = fx >= fy ? h00 + fx * (h10 - h00) + fy * (h11 - h10) : h00 + fy * (h01 - h00) + fx * (h11 - h01);
  return std::abs(hf.at(x, y) - i);
}

LodErrorMap::LodErrorMap(const Heightfield& hf, int levels, int threads) {
  levels = std::clamp(levels, 1, 24);
  levels_.resize(size_t(levels));
  for (int l = 0; l < levels; ++l) {
    Level& lv = levels_[size_t(l)];
    lv.block = std::max(kTileSize, 1 << l);
    lv.nx = (hf.samplesX() + lv.block - 1) / lv.block;
    lv.ny = (hf.samplesY() + lv.block - 1) / lv.block;
    lv.blockError.assign(size_t(lv.nx) * size_t(lv.ny), 0.0f);
  }
  update(hf, hf.bounds(), threads);
}

float LodErrorMap::error(int level) const {
  if (monotone_.empty() || level <= 0) return 0.0f;
  return monotone_[size_t(std::min(level, int(monotone_.size()) - 1))];
}

void LodErrorMap::computeBlocks(const Heightfield& hf, int level, const std::vector<int>& blocks, int threads) {
  // Levels [level, last] share this level's block size (all those up to the
  // tile size do): one window read per block serves them all.
  Level& lv = levels_[size_t(level)];
  const int B = lv.block;
  int last = level;
  while (last + 1 < levels() && levels_[size_t(last + 1)].block == B) ++last;
  const int count = int(blocks.size()), n = last - level + 1;
  std::vector<float> out(size_t(count) * size_t(n));
  parallelFor(count, threads, 1, [&](int b, int e) {
    Window win;
    for (int i = b; i < e; ++i) {
      const int bx = blocks[size_t(i)] % lv.nx, by = blocks[size_t(i)] / lv.nx;
      readWindow(hf, bx * B, by * B, B, B, win);
      for (int l = level; l <= last; ++l)
        out[size_t(i) * size_t(n) + size_t(l - level)] =
            blockError(win, 1 << l, bx * B, by * B, B, B, hf.samplesX(), hf.samplesY());
    }
  });
  for (int l = level; l <= last; ++l)
    for (int i = 0; i < count; ++i)
      levels_[size_t(l)].blockError[size_t(blocks[size_t(i)])] = out[size_t(i) * size_t(n) + size_t(l - level)];
  evaluated_ += size_t(count) * size_t(B) * size_t(B) * size_t(n);
}

size_t LodErrorMap::update(const Heightfield& hf, const Region& changed, int threads) {
  return update(hf, std::vector<Region>{changed}, threads);
}

size_t LodErrorMap::update(const Heightfield& hf, const std::vector<Region>& changed, int threads) {
  evaluated_ = 0;
  if (levels_.empty()) return 0;
  bool any = false;
  for (int l = 1; l < levels(); ++l) {
    // Levels with the block size of the one before were done with it.
    if (l > 1 && levels_[size_t(l)].block == levels_[size_t(l - 1)].block) continue;
    const Level& lv = levels_[size_t(l)];
    std::vector<uint8_t> mark(lv.blockError.size(), 0);
    std::vector<int> blocks;
    for (const Region& c : changed) {
      const Region r = c.intersected(hf.bounds());
      if (r.empty()) continue;
      // A changed sample on a block's low edge is also the far corner of the
      // previous block's last coarse cells.
      const int bx0 = std::max(0, (r.x0 - 1) / lv.block), by0 = std::max(0, (r.y0 - 1) / lv.block);
      const int bx1 = std::min(lv.nx - 1, (r.x1 - 1) / lv.block), by1 = std::min(lv.ny - 1, (r.y1 - 1) / lv.block);
      for (int by = by0; by <= by1; ++by)
        for (int bx = bx0; bx <= bx1; ++bx) {
          const int i = by * lv.nx + bx;
          if (!mark[size_t(i)]) {
            mark[size_t(i)] = 1;
            blocks.push_back(i);
          }
        }
    }
    if (blocks.empty()) continue;
    any = true;
    computeBlocks(hf, l, blocks, threads);
  }
  if (any) refreshMax();
  return evaluated_;
}

void LodErrorMap::refreshMax() {
  monotone_.assign(levels_.size(), 0.0f);
  float running = 0.0f;
  for (size_t l = 0; l < levels_.size(); ++l) {
    Level& lv = levels_[l];
    lv.max = lv.blockError.empty() ? 0.0f : *std::max_element(lv.blockError.begin(), lv.blockError.end());
    running = std::max(running, lv.max);
    monotone_[l] = running;
  }
}

}  // namespace hs::terrain
