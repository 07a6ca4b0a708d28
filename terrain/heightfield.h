#pragma once
// A terrain's heights: float samples on a regular grid (at most 8193 x 8193),
// stored in 128^2 tiles (tile_grid.h), placed in the world by a double origin
// (DESIGN.md: float data relative to a double origin, so a terrain at UTM
// coordinates keeps millimetre precision), with a holes mask that removes
// cells from drawing and picking. Several terrains in a scene are several
// Heightfield objects, each with its own origin.
//
// Conventions: X east, Y north, Z up, metres. Sample (i, j) sits at
// origin + (i * spacing.x, j * spacing.y, height(i, j)); row j = 0 is the
// southern edge (images and DEMs store north first: import/export flip).
// A cell (quad) (i, j) spans samples i..i+1, j..j+1 and is drawn as two
// triangles split along (i, j)-(i+1, j+1); it is a hole when any of its four
// corner samples is marked.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "terrain/region.h"
#include "terrain/result.h"
#include "terrain/tile_grid.h"

namespace hs::terrain {

constexpr int kMaxSamples = 8193;  // 2^13 + 1 per side
constexpr int kMinSamples = 2;

// Georeferencing kept from an imported DEM so exports line up with it. The
// terrain's origin is expressed in this CRS (e.g. UTM easting/northing).
struct GeoReference {
  std::string crsWkt;   // empty: a local terrain with no CRS
  std::string crsName;  // human-readable, e.g. "WGS 84 / UTM zone 14N"
  int epsg = 0;         // 0 when unknown
  bool valid() const { return !crsWkt.empty(); }
};

// What a new terrain looks like (New Terrain dialog, CLI, JSON description).
struct HeightfieldDesc {
  int samplesX = 1025, samplesY = 1025;
  glm::dvec2 sizeMetres{1024.0, 1024.0};  // extent from the first to the last sample
  glm::dvec3 origin{0.0};                  // world position of sample (0,0) at height 0
  float initialHeight = 0.0f;
  GeoReference geo;
};

struct HeightRange {
  float min = 0.0f, max = 0.0f;
};

// Min and max of n floats into lo/hi (vectorised; heights are finite).
void minMaxSpan(const float* p, int n, float& lo, float& hi);

class Heightfield {
 public:
  Heightfield() = default;
  // Checks the description (sizes 2..8193, finite positive extent) and
  // allocates every height tile.
  static Result<Heightfield> create(const HeightfieldDesc& desc);

  Heightfield(Heightfield&&) noexcept = default;
  Heightfield& operator=(Heightfield&&) noexcept = default;
  Heightfield clone() const;

  // --- layout -------------------------------------------------------------
  int samplesX() const { return heights_.width(); }
  int samplesY() const { return heights_.height(); }
  Region bounds() const { return {0, 0, samplesX(), samplesY()}; }
  glm::dvec2 spacing() const { return spacing_; }
  // Restores a spacing exactly (a file keeps the double itself: size / (n-1)
  // recomputed from a saved size need not give back the same bits). Ignores
  // non-finite or non-positive values.
  void setSpacing(const glm::dvec2& s) {
    if (std::isfinite(s.x) && std::isfinite(s.y) && s.x > 0.0 && s.y > 0.0) spacing_ = s;
  }
  glm::dvec2 sizeMetres() const { return spacing_ * glm::dvec2(samplesX() - 1, samplesY() - 1); }
  const glm::dvec3& origin() const { return origin_; }
  // Places the samples elsewhere (a terrain entity's world origin, for
  // tools that work in world coordinates on a copy-on-write clone).
  void setOrigin(const glm::dvec3& o) { origin_ = o; }
  const GeoReference& geo() const { return geo_; }
  void setGeo(GeoReference g) { geo_ = std::move(g); }
  HeightfieldDesc desc() const;

  // --- samples ------------------------------------------------------------
  float at(int x, int y) const { return heights_.get(x, y); }
  float atClamped(int x, int y) const;
  void set(int x, int y, float h);  // also refreshes the tile bounds lazily
  TileGrid<float>& heights() { return heights_; }
  const TileGrid<float>& heights() const { return heights_; }
  // Copies a region into a row-major array (width * height) and back.
  std::vector<float> read(const Region& r) const;
  void write(const Region& r, const std::vector<float>& values);

  // --- holes --------------------------------------------------------------
  bool isHole(int x, int y) const { return holes_.get(x, y) != 0; }
  void setHole(int x, int y, bool hole);
  bool cellIsHole(int cx, int cy) const;
  TileGrid<uint8_t>& holes() { return holes_; }
  const TileGrid<uint8_t>& holes() const { return holes_; }

  // --- queries (local metres: relative to origin; world: absolute) --------
  glm::dvec2 worldToLocal(const glm::dvec2& w) const { return w - glm::dvec2(origin_); }
  glm::dvec2 localToSample(const glm::dvec2& l) const { return l / spacing_; }
  // Bilinear height at a local position, clamped to the grid; ignores holes.
  float heightAtLocal(const glm::dvec2& local) const;
  // Surface height (world Z) at a world XY, or nullopt outside the terrain or in a hole.
  std::optional<double> surfaceAtWorld(const glm::dvec2& world) const;
  // Unit normal from the bilinearly interpolated central-difference gradient.
  glm::vec3 normalAtLocal(const glm::dvec2& local) const;
  // Gradient dh/dx, dh/dy (metres per metre) at a sample (central differences).
  glm::vec2 gradientAt(int x, int y) const;

  // --- bounds (CDLOD, picking) ----------------------------------------------
  // Min/max over the samples of tile t's cells: samples [x0, x0+128] x
  // [y0, y0+128] (the shared edge included, so every cell of the tile is
  // bounded). Kept up to date by every edit through updateBounds().
  HeightRange tileBounds(int t) const;
  HeightRange range() const;  // over the whole terrain
  // Recomputes the bounds of tiles whose cells include samples in `changed`.
  void updateBounds(const Region& changed);
  void updateAllBounds();

  size_t memoryBytes() const;

 private:
  TileGrid<float> heights_;
  TileGrid<uint8_t> holes_;  // sparse; 1 = hole
  std::vector<HeightRange> tileBounds_;
  glm::dvec2 spacing_{1.0};
  glm::dvec3 origin_{0.0};
  GeoReference geo_;
};

}  // namespace hs::terrain
