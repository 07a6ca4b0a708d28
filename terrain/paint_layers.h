#pragma once
// Paint layers: a list of materials and, per material, a weight per height
// sample, tiled like the heights (128^2 tiles, allocated on first write, so a
// layer that is painted in one corner costs one corner).
//
// Weights are 16-bit integers that sum to exactly 65535 at every sample after
// every operation: each blend computes the new weights in integers and hands
// out the rounding remainder by largest remainder, so "weights sum to 1" is an
// invariant, not an approximation (65535 steps: a 1% brush still moves a
// weight by 655 steps, where Unreal's 8-bit weights lose gentle strokes).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "terrain/region.h"
#include "terrain/result.h"
#include "terrain/tile_grid.h"

namespace hs::terrain {

constexpr int kMaxPaintLayers = 16;
constexpr uint16_t kWeightOne = 65535;
// A 16-bit weight as 8 bits, rounded to nearest (raw * 255 / 65535 is
// never exactly halfway): what an 8-bit splat map and the renderer's weight
// texture hold, so the two agree.
constexpr uint8_t weightByte(uint16_t raw) { return uint8_t((uint32_t(raw) * 255u + 32767u) / 65535u); }

struct Material {
  std::string name = "Material";
  glm::vec3 albedo{0.5f};          // linear RGB, used when there is no texture and as a tint
  std::string albedoTexture;       // path, may be empty
  std::string normalTexture;       // path, may be empty
  float roughness = 0.8f;
  float tilingMetres = 4.0f;       // world size of one texture repeat
  bool operator==(const Material&) const = default;
};

// The eight materials of a new terrain (the Meteora job's palette).
std::vector<Material> defaultMaterials();

class PaintLayers {
 public:
  PaintLayers() = default;
  // Layer 0 starts at weight 1 everywhere (the base material).
  static Result<PaintLayers> create(int samplesX, int samplesY, std::vector<Material> materials);
  PaintLayers(PaintLayers&&) noexcept = default;
  PaintLayers& operator=(PaintLayers&&) noexcept = default;
  PaintLayers clone() const;

  int samplesX() const { return samplesX_; }
  int samplesY() const { return samplesY_; }
  int layerCount() const { return int(materials_.size()); }
  const Material& material(int i) const { return materials_[size_t(i)]; }
  Status setMaterial(int i, Material m);
  // A new layer with weight 0 everywhere.
  Result<int> addLayer(Material m);
  // Removes a layer; its weight goes to the other layers in proportion (to
  // layer 0, or layer 1 when removing layer 0, where no other layer has
  // weight). Cannot remove the last layer. Layers above it move down one.
  Status removeLayer(int layer);

  uint16_t raw(int layer, int x, int y) const { return weights_[size_t(layer)].get(x, y); }
  float weight(int layer, int x, int y) const { return float(raw(layer, x, y)) / float(kWeightOne); }
  // Bilinear weight at a sample-space position (foliage density lookups).
  float weightAt(int layer, const glm::dvec2& samplePos) const;
  TileGrid<uint16_t>& grid(int layer) { return weights_[size_t(layer)]; }
  const TileGrid<uint16_t>& grid(int layer) const { return weights_[size_t(layer)]; }

  // Moves the weights of one sample toward `layer` by `amount` in [0,1]
  // (w' = w + amount * (1 - w), the others scaled by 1 - amount); a negative
  // amount erases `layer` and gives its weight to the others in proportion.
  void blend(int x, int y, int layer, float amount);

  // Prepares the tiles under `r` for a blend toward `layer` from worker
  // threads: allocates what blendPrepared() may write. Not thread-safe itself.
  void prepareBlend(const Region& r, int layer);
  // Same as blend() on prepared tiles; safe from several threads on disjoint samples.
  void blendPrepared(int x, int y, int layer, float amount);
  // Frees tiles under `r` that became all-zero (or all-65535 on layer 0).
  void releaseUniformTiles(const Region& r);

  // Largest |sum - 1| over the samples of `r` (a check; 0 by construction).
  double maxSumError(const Region& r) const;
  size_t memoryBytes() const;

 private:
  // A copy of `g` (tiles shared) whose unallocated tiles read `fill`.
  static TileGrid<uint16_t> withFill(const TileGrid<uint16_t>& g, uint16_t fill);
  int fallbackFor(int layer) const { return layer == 0 ? (layerCount() > 1 ? 1 : 0) : 0; }
  int samplesX_ = 0, samplesY_ = 0;
  std::vector<Material> materials_;
  std::vector<TileGrid<uint16_t>> weights_;
};

// The integer core of every blend: `q` holds n weights summing to 65535;
// moves them toward `layer` by `amount` (negative: erase, freed weight to the
// others in proportion, or to `fallback` when none has weight).
void blendWeights(uint16_t* q, int n, int layer, float amount, int fallback);

}  // namespace hs::terrain
