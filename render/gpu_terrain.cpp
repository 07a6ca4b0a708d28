#include "render/gpu_terrain.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <set>

#include "terrain/paint_layers.h"

namespace hs::render {
namespace {

using terrain::kTileSize;
using terrain::Region;

// Tile rows are kTileSize samples apart: with this row length GL reads a
// sub-rectangle straight out of a tile, without repacking.
void unpackFromTiles() {
  glPixelStorei(GL_UNPACK_ROW_LENGTH, kTileSize);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
}

void unpackDefaults() {
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

// Per-tile dirty rectangles: several dabs between two frames upload each
// sample once.
void addDirty(std::map<int, Region>& dirty, const terrain::TileGrid<float>& layout, const Region& r) {
  layout.forEachTile(r, [&](int t, const Region& part) {
    auto [it, inserted] = dirty.emplace(t, part);
    if (!inserted) it->second = it->second.united(part);
  });
}

}  // namespace

void GpuTerrain::release() {
  GLuint tex[3] = {height_, holes_, weights_};
  glDeleteTextures(3, tex);
  height_ = holes_ = weights_ = 0;
  slice_.clear();
  slices_ = 0;
  instance_ = 0;
}

size_t GpuTerrain::gpuBytes() const {
  const size_t n = size_t(w_) * size_t(h_);
  return (height_ ? n * 4 : 0) + (holes_ ? n : 0) + (weights_ ? n * 4 * size_t(weightGroups()) : 0);
}

void GpuTerrain::createHeights(const scene::TerrainData& data) {
  release();
  const terrain::Heightfield& hf = data.heights();
  w_ = hf.samplesX();
  h_ = hf.samplesY();
  instance_ = data.instance();
  glCreateTextures(GL_TEXTURE_2D, 1, &height_);
  glTextureStorage2D(height_, 1, GL_R32F, w_, h_);
  // Linear filtering for the fragment shader's normals (bilinear central
  // differences); the vertex shader reads exact texels.
  glTextureParameteri(height_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(height_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(height_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(height_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void GpuTerrain::uploadHeights(const terrain::Heightfield& hf, const Region& r, TerrainUploadStats& s) {
  const auto& g = hf.heights();
  unpackFromTiles();
  g.forEachTile(r, [&](int t, const Region& part) {
    const float* tile = g.tile(t);
    if (!tile) {  // heights are dense; kept for safety
      const float fill = g.fill();
      glClearTexSubImage(height_, 0, part.x0, part.y0, 0, part.width(), part.height(), 1, GL_RED, GL_FLOAT, &fill);
    } else {
      glTextureSubImage2D(height_, 0, part.x0, part.y0, part.width(), part.height(), GL_RED, GL_FLOAT,
                          tile + terrain::TileGrid<float>::localIndex(part.x0, part.y0));
      s.bytes += part.samples() * 4;
    }
    ++s.regions;
  });
  unpackDefaults();
}

bool GpuTerrain::ensureHoles(const terrain::Heightfield& hf, TerrainUploadStats& s) {
  if (holes_ || hf.holes().allocatedTiles() == 0) return false;
  glCreateTextures(GL_TEXTURE_2D, 1, &holes_);
  glTextureStorage2D(holes_, 1, GL_R8UI, w_, h_);
  glTextureParameteri(holes_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(holes_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  uploadHoles(hf, hf.bounds(), s);
  return true;
}

void GpuTerrain::uploadHoles(const terrain::Heightfield& hf, const Region& r, TerrainUploadStats& s) {
  if (!holes_) return;
  const auto& g = hf.holes();
  unpackFromTiles();
  g.forEachTile(r, [&](int t, const Region& part) {
    const uint8_t* tile = g.tile(t);
    if (!tile) {
      const uint8_t zero = 0;
      glClearTexSubImage(holes_, 0, part.x0, part.y0, 0, part.width(), part.height(), 1, GL_RED_INTEGER,
                         GL_UNSIGNED_BYTE, &zero);
    } else {
      glTextureSubImage2D(holes_, 0, part.x0, part.y0, part.width(), part.height(), GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                          tile + terrain::TileGrid<uint8_t>::localIndex(part.x0, part.y0));
      s.bytes += part.samples();
    }
    ++s.regions;
  });
  unpackDefaults();
}

bool GpuTerrain::ensureWeights(const terrain::PaintLayers& paint, TerrainUploadStats& s) {
  // A layer gets a slice once it has painted tiles; slices are never given
  // back (no reallocation churn while painting).
  std::vector<int> want = slice_;
  want.resize(size_t(paint.layerCount()), -1);
  int count = slices_;
  for (int l = 0; l < paint.layerCount(); ++l)
    if (want[size_t(l)] < 0 && paint.grid(l).allocatedTiles() > 0) want[size_t(l)] = count++;
  if (count == slices_ && weights_) {
    slice_ = want;
    return false;
  }
  slice_ = want;
  if (count == 0) return false;
  if (weights_) glDeleteTextures(1, &weights_);
  slices_ = count;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &weights_);
  glTextureStorage3D(weights_, 1, GL_RGBA8, w_, h_, weightGroups());
  glTextureParameteri(weights_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(weights_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(weights_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(weights_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  uploadWeights(paint, Region{0, 0, w_, h_}, s);
  return true;
}

void GpuTerrain::uploadWeights(const terrain::PaintLayers& paint, const Region& r, TerrainUploadStats& s) {
  if (!weights_) return;
  // The layers in each group of four slices (-1: a channel no layer uses).
  std::vector<std::array<int, 4>> groups(size_t(weightGroups()), {-1, -1, -1, -1});
  for (int l = 0; l < paint.layerCount(); ++l)
    if (const int slice = weightSlice(l); slice >= 0) groups[size_t(slice / 4)][size_t(slice % 4)] = l;
  // Repacked here (four layers' tiles into one RGBA8 rectangle), so rows
  // are tight, not tile rows, whatever unpacking state another upload left.
  unpackDefaults();
  std::vector<uint8_t> texels;
  for (size_t g = 0; g < groups.size(); ++g) {
    paint.grid(0).forEachTile(r, [&](int t, const Region& part) {
      texels.assign(part.samples() * 4, 0);
      for (int c = 0; c < 4; ++c) {
        const int layer = groups[g][size_t(c)];
        if (layer < 0) continue;
        const auto& grid = paint.grid(layer);
        const uint16_t* tile = grid.tile(t);
        for (int y = 0; y < part.height(); ++y)
          for (int x = 0; x < part.width(); ++x) {
            const uint16_t v =
                tile ? tile[terrain::TileGrid<uint16_t>::localIndex(part.x0 + x, part.y0 + y)] : grid.fill();
            texels[(size_t(y) * size_t(part.width()) + size_t(x)) * 4 + size_t(c)] = terrain::weightByte(v);
          }
      }
      glTextureSubImage3D(weights_, 0, part.x0, part.y0, GLint(g), part.width(), part.height(), 1, GL_RGBA,
                          GL_UNSIGNED_BYTE, texels.data());
      s.bytes += texels.size();
      ++s.regions;
    });
  }
}

TerrainUploadStats GpuTerrain::sync(const scene::TerrainData& data) {
  TerrainUploadStats s;
  const auto t0 = std::chrono::steady_clock::now();
  const terrain::Terrain& tr = data.terrain();
  const terrain::Heightfield& hf = tr.height;
  std::vector<scene::TerrainChange> changes;
  const bool fresh = instance_ != data.instance() || w_ != hf.samplesX() || h_ != hf.samplesY();
  if (fresh || !data.changesSince(serial_, changes)) {
    if (fresh) createHeights(data);
    s.full = true;
    uploadHeights(hf, hf.bounds(), s);
    if (!ensureHoles(hf, s)) uploadHoles(hf, hf.bounds(), s);
    if (!ensureWeights(tr.paint, s)) uploadWeights(tr.paint, hf.bounds(), s);
    const auto l0 = std::chrono::steady_clock::now();
    tree_ = terrain::MinMaxTree(hf, kTerrainGridQuads);
    error_ = terrain::LodErrorMap(hf, tree_.levels());
    s.lodMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - l0).count();
  } else if (!changes.empty()) {
    std::map<int, Region> heights, holes, paint;
    for (const scene::TerrainChange& c : changes) {
      if (c.kinds & scene::kTerrainHeights) addDirty(heights, hf.heights(), c.region);
      if (c.kinds & scene::kTerrainHoles) addDirty(holes, hf.heights(), c.region);
      if (c.kinds & scene::kTerrainPaint) addDirty(paint, hf.heights(), c.region);
    }
    std::vector<Region> regions;
    for (const auto& [t, r] : heights) {
      uploadHeights(hf, r, s);
      regions.push_back(r);
    }
    const auto l0 = std::chrono::steady_clock::now();
    for (const Region& r : regions) tree_.update(hf, r);
    if (!regions.empty()) error_.update(hf, regions);
    s.lodMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - l0).count();
    if (!holes.empty() && !ensureHoles(hf, s))
      for (const auto& [t, r] : holes) uploadHoles(hf, r, s);
    if (!paint.empty() && !ensureWeights(tr.paint, s))
      for (const auto& [t, r] : paint) uploadWeights(tr.paint, r, s);
  }
  serial_ = data.serial();
  s.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

GpuTerrain* GpuTerrainCache::get(const scene::TerrainData& data, TerrainUploadStats* stats) {
  auto& slot = terrains_[data.instance()];
  if (!slot) slot = std::make_unique<GpuTerrain>();
  const TerrainUploadStats s = slot->sync(data);
  if (stats) {
    stats->bytes += s.bytes;
    stats->regions += s.regions;
    stats->cpuMs += s.cpuMs;
    stats->lodMs += s.lodMs;
    stats->full = stats->full || s.full;
  }
  return slot.get();
}

void GpuTerrainCache::collect(const scene::SceneState& state) {
  std::set<uint64_t> live;
  for (const auto& [id, t] : state.terrains)
    if (t.data) live.insert(t.data->instance());
  for (auto it = terrains_.begin(); it != terrains_.end();) {
    if (live.count(it->first)) {
      ++it;
    } else {
      it->second->release();
      it = terrains_.erase(it);
    }
  }
}

void GpuTerrainCache::clear() {
  for (auto& [id, t] : terrains_) t->release();
  terrains_.clear();
}

size_t GpuTerrainCache::gpuBytes() const {
  size_t b = 0;
  for (const auto& [id, t] : terrains_) b += t->gpuBytes();
  return b;
}

}  // namespace hs::render
