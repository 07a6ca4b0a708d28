#include "terrain/paint_layers.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace hs::terrain {

std::vector<Material> defaultMaterials() {
  auto m = [](const char* name, glm::vec3 albedo, float rough, float tiling) {
    Material r;
    r.name = name;
    r.albedo = albedo;
    r.roughness = rough;
    r.tilingMetres = tiling;
    return r;
  };
  return {m("Soil", {0.30f, 0.22f, 0.15f}, 0.9f, 4.0f),       m("Grass", {0.18f, 0.30f, 0.08f}, 0.85f, 3.0f),
          m("Sandstone", {0.55f, 0.45f, 0.33f}, 0.75f, 8.0f), m("Conglomerate", {0.45f, 0.40f, 0.35f}, 0.8f, 6.0f),
          m("Scree", {0.50f, 0.48f, 0.45f}, 0.85f, 4.0f),     m("Forest floor", {0.16f, 0.13f, 0.08f}, 0.95f, 3.0f),
          m("Riverbed", {0.40f, 0.38f, 0.33f}, 0.6f, 2.0f),   m("Snow", {0.85f, 0.87f, 0.90f}, 0.4f, 5.0f)};
}

Result<PaintLayers> PaintLayers::create(int samplesX, int samplesY, std::vector<Material> materials) {
  if (materials.empty()) materials = defaultMaterials();
  if (int(materials.size()) > kMaxPaintLayers)
    return Result<PaintLayers>::failure("at most " + std::to_string(kMaxPaintLayers) + " paint layers");
  if (samplesX < 2 || samplesY < 2 || samplesX > 8193 || samplesY > 8193)
    return Result<PaintLayers>::failure("paint layer size outside 2..8193 samples");
  PaintLayers p;
  p.samplesX_ = samplesX;
  p.samplesY_ = samplesY;
  p.materials_ = std::move(materials);
  for (size_t i = 0; i < p.materials_.size(); ++i)
    p.weights_.emplace_back(samplesX, samplesY, uint16_t(i == 0 ? kWeightOne : 0), /*dense=*/false);
  return p;
}

PaintLayers PaintLayers::clone() const {
  PaintLayers p;
  p.samplesX_ = samplesX_;
  p.samplesY_ = samplesY_;
  p.materials_ = materials_;
  for (const auto& g : weights_) p.weights_.push_back(g.clone());
  return p;
}

Status PaintLayers::setMaterial(int i, Material m) {
  if (i < 0 || i >= layerCount()) return Status::failure("no paint layer " + std::to_string(i));
  if (!std::isfinite(m.roughness) || !std::isfinite(m.tilingMetres) || m.tilingMetres <= 0.0f)
    return Status::failure("material '" + m.name + "': roughness and tiling must be finite, tiling > 0");
  m.roughness = std::clamp(m.roughness, 0.0f, 1.0f);
  materials_[size_t(i)] = std::move(m);
  return {};
}

Result<int> PaintLayers::addLayer(Material m) {
  if (layerCount() >= kMaxPaintLayers)
    return Result<int>::failure("at most " + std::to_string(kMaxPaintLayers) + " paint layers");
  materials_.push_back(std::move(m));
  weights_.emplace_back(samplesX_, samplesY_, uint16_t(0), false);
  return layerCount() - 1;
}

Status PaintLayers::removeLayer(int layer) {
  if (layer < 0 || layer >= layerCount()) return Status::failure("no paint layer " + std::to_string(layer));
  if (layerCount() == 1) return Status::failure("a terrain keeps at least one paint layer");
  // Erase the layer completely wherever it has weight, then drop it. Only
  // tiles where it can have weight are visited (an unpainted tile of a layer
  // other than 0 holds none), so removing a layer painted in one corner of an
  // 8k terrain costs that corner. Tiles are prepared on this thread, then
  // blended on the pool (each sample written once: same bits on any count).
  const TileGrid<uint16_t>& g = weights_[size_t(layer)];
  std::vector<int> tiles;
  for (int t = 0; t < g.tileCount(); ++t)
    if (g.allocated(t) || g.fill() != 0) tiles.push_back(t);
  for (int t : tiles) prepareBlend(g.tileRegion(t), -1 - layer);
  parallelFor(int(tiles.size()), 0, 4, [&](int b, int e) {
    for (int i = b; i < e; ++i) {
      const Region r = g.tileRegion(tiles[size_t(i)]);
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
          if (raw(layer, x, y)) blendPrepared(x, y, layer, -1.0f);
    }
  });
  materials_.erase(materials_.begin() + layer);
  weights_.erase(weights_.begin() + layer);
  // Layer 0 reads 1 where it has no tile and every other layer 0 (the file
  // format and the renderer rely on it): when layer 0 itself went, the new
  // first layer takes that fill.
  if (layer == 0) weights_[0] = withFill(weights_[0], kWeightOne);
  releaseUniformTiles(Region{0, 0, samplesX_, samplesY_});
  return {};
}

TileGrid<uint16_t> PaintLayers::withFill(const TileGrid<uint16_t>& g, uint16_t fill) {
  TileGrid<uint16_t> out(g.width(), g.height(), fill, false);
  for (int t = 0; t < g.tileCount(); ++t) {
    if (g.allocated(t)) {
      out.setTile(t, g.sharedTile(t));
      const Region r = out.tileRegion(t);
      if (g.fill() != fill && (r.width() < kTileSize || r.height() < kTileSize)) {
        // Samples past the grid's edge still hold the old fill: give them
        // the new one, or a tile reading `fill` everywhere is never released.
        uint16_t* p = out.tileForWrite(t);
        for (int y = 0; y < kTileSize; ++y)
          for (int x = 0; x < kTileSize; ++x)
            if (x >= r.width() || y >= r.height()) p[(y << kTileShift) | x] = fill;
      }
    } else if (g.fill() != fill) {
      // It read g.fill(): write that inside the grid (the rest keeps `fill`).
      uint16_t* p = out.tileForWrite(t);
      const Region r = out.tileRegion(t);
      for (int y = 0; y < r.height(); ++y) std::fill_n(p + (y << kTileShift), r.width(), g.fill());
    }
  }
  return out;
}

float PaintLayers::weightAt(int layer, const glm::dvec2& s) const {
  const double fx = std::clamp(s.x, 0.0, double(samplesX_ - 1)), fy = std::clamp(s.y, 0.0, double(samplesY_ - 1));
  const int x0 = std::min(int(fx), samplesX_ - 2), y0 = std::min(int(fy), samplesY_ - 2);
  const float tx = float(fx - x0), ty = float(fy - y0);
  return (weight(layer, x0, y0) * (1 - tx) + weight(layer, x0 + 1, y0) * tx) * (1 - ty) +
         (weight(layer, x0, y0 + 1) * (1 - tx) + weight(layer, x0 + 1, y0 + 1) * tx) * ty;
}

void blendWeights(uint16_t* q, int n, int layer, float amount, int fallback) {
  if (!(amount == amount) || amount == 0.0f || n <= 1) return;  // NaN, nothing to do, or one layer (always 1)
  amount = std::clamp(amount, -1.0f, 1.0f);
  constexpr int64_t Q = kWeightOne;
  const int64_t qk = q[layer];
  int64_t newK;
  if (amount > 0.0f)
    newK = qk + int64_t(std::lround(double(amount) * double(Q - qk)));
  else
    newK = int64_t(std::lround(double(qk) * (1.0 + double(amount))));
  newK = std::clamp<int64_t>(newK, 0, Q);
  if (newK == qk) return;
  const int64_t othersOld = Q - qk, othersNew = Q - newK;
  q[layer] = uint16_t(newK);
  if (othersOld == 0) {
    // Only `layer` had weight: what it gives up goes to the fallback layer.
    const int f = fallback == layer ? (layer + 1) % n : fallback;
    q[f] = uint16_t(othersNew);
    return;
  }
  // Scale the others from othersOld to othersNew: floor, then hand the
  // remainder to the largest fractional parts (ties: lower index first).
  int64_t given = 0;
  int64_t rem[kMaxPaintLayers];
  for (int j = 0; j < n; ++j) {
    rem[j] = -1;
    if (j == layer || q[j] == 0) continue;
    const int64_t num = int64_t(q[j]) * othersNew;
    q[j] = uint16_t(num / othersOld);
    rem[j] = num % othersOld;
    given += q[j];
  }
  for (int64_t left = othersNew - given; left > 0; --left) {
    int best = -1;
    for (int j = 0; j < n; ++j)
      if (rem[j] >= 0 && (best < 0 || rem[j] > rem[best])) best = j;
    if (best < 0) break;
    ++q[best];
    rem[best] = -1;
  }
}

void PaintLayers::blend(int x, int y, int layer, float amount) {
  if (layer < 0 || layer >= layerCount()) return;
  prepareBlend(Region{x, y, x + 1, y + 1}, layer);
  blendPrepared(x, y, layer, amount);
}

void PaintLayers::prepareBlend(const Region& r, int layer) {
  // `layer` < 0 encodes "erase layer -1-layer" for removeLayer().
  const int target = layer < 0 ? -1 - layer : layer;
  const int fallback = fallbackFor(target);
  for (int l = 0; l < layerCount(); ++l) {
    auto& g = weights_[size_t(l)];
    g.forEachTile(r, [&](int t, const Region&) {
      if (l == target || l == fallback || g.allocated(t) || g.fill() != 0) g.tileForWrite(t);
    });
  }
}

void PaintLayers::blendPrepared(int x, int y, int layer, float amount) {
  const int n = layerCount();
  uint16_t q[kMaxPaintLayers];
  uint16_t* ptr[kMaxPaintLayers];
  const int li = TileGrid<uint16_t>::localIndex(x, y);
  const int t = weights_[0].tileIndex(x, y);
  for (int l = 0; l < n; ++l) {
    uint16_t* tile = weights_[size_t(l)].preparedTile(t);
    ptr[l] = tile ? tile + li : nullptr;
    q[l] = tile ? tile[li] : weights_[size_t(l)].fill();
  }
  blendWeights(q, n, layer, amount, fallbackFor(layer));
  for (int l = 0; l < n; ++l)
    if (ptr[l]) *ptr[l] = q[l];
}

void PaintLayers::releaseUniformTiles(const Region& r) {
  for (auto& g : weights_) g.forEachTile(r, [&](int t, const Region&) { g.releaseIfUniform(t); });
}

double PaintLayers::maxSumError(const Region& region) const {
  const Region r = region.intersected({0, 0, samplesX_, samplesY_});
  double worst = 0.0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      double s = 0.0;
      for (int l = 0; l < layerCount(); ++l) s += double(weight(l, x, y));
      worst = std::max(worst, std::abs(s - 1.0));
    }
  return worst;
}

size_t PaintLayers::memoryBytes() const {
  size_t b = 0;
  for (const auto& g : weights_) b += g.memoryBytes();
  return b;
}

}  // namespace hs::terrain
