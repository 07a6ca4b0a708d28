#include "scene/terrain_data.h"

#include <cstring>

#include "terrain/tile_hash.h"

namespace hs::scene {
namespace {

std::atomic<uint64_t> nextInstance{1};
// Enough for a long stroke between two frames; older history means the
// renderer simply re-uploads the whole terrain once.
constexpr size_t kLogEntries = 1024;

}  // namespace

std::vector<TileHashCache::Entry>& TileHashCache::entriesFor(hs::terrain::TileKind kind, int layer, int tile) {
  const size_t g = kind == hs::terrain::TileKind::Height ? 0 : kind == hs::terrain::TileKind::Holes ? 1 : 2 + size_t(layer);
  if (grids_.size() <= g) grids_.resize(g + 1);
  auto& v = grids_[g];
  if (v.size() <= size_t(tile)) v.resize(size_t(tile) + 1);
  return v;
}

uint64_t TileHashCache::get(hs::terrain::TileKind kind, int layer, int tile, uint64_t revision, const void* data,
                            size_t bytes, const void* fill, size_t sampleBytes) {
  if (!data) return 0;
  {
    std::lock_guard lock(mutex_);
    const Entry& e = entriesFor(kind, layer, tile)[size_t(tile)];
    if (e.revision == revision) return e.hash;
  }
  // Hash outside the lock: two threads may both compute it; same result.
  const uint64_t h = compute(&hs::terrain::tileContentHash, kind, layer, tile, data, bytes, fill, sampleBytes);
  put(kind, layer, tile, revision, h);
  return h;
}

uint64_t TileHashCache::compute(HashFunction hash, hs::terrain::TileKind kind, int layer, int tile, const void* data,
                                size_t bytes, const void* fill, size_t sampleBytes) {
  if (!data) return 0;
  bool onlyFill = fill != nullptr;
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; onlyFill && i < bytes; i += sampleBytes) onlyFill = std::memcmp(p + i, fill, sampleBytes) == 0;
  return onlyFill ? 0 : hash(kind, layer, tile, data, bytes);
}

void TileHashCache::put(hs::terrain::TileKind kind, int layer, int tile, uint64_t revision, uint64_t hash) {
  std::lock_guard lock(mutex_);
  Entry& e = entriesFor(kind, layer, tile)[size_t(tile)];
  e.revision = revision;
  e.hash = hash;
}

TerrainData::TerrainData(hs::terrain::Terrain t)
    : terrain_(std::move(t)), instance_(nextInstance++), hashes_(std::make_shared<TileHashCache>()) {}

void TerrainData::noteChanged(const hs::terrain::Region& region, uint8_t kinds) {
  if (region.empty() || !kinds) return;
  described_.reset();
  log_.push_back({++serial_, region, kinds});
  while (log_.size() > kLogEntries) log_.pop_front();
}

bool TerrainData::changesSince(uint64_t since, std::vector<TerrainChange>& out) const {
  out.clear();
  if (since >= serial_) return true;
  if (log_.empty() || log_.front().serial > since + 1) return false;
  for (const TerrainChange& c : log_)
    if (c.serial > since) out.push_back(c);
  return true;
}

std::shared_ptr<TerrainData> TerrainData::snapshot() const {
  auto s = std::make_shared<TerrainData>(terrain_.clone());
  s->hashes_ = hashes_;
  s->serial_ = serial_;
  s->described_ = described_;
  return s;
}

uint64_t TerrainData::tileHash(hs::terrain::TileKind kind, int layer, int tile,
                              TileHashCache::HashFunction legacy) const {
  auto hash = [&](const auto& grid, int l, const void* fill, size_t sampleBytes) {
    if (legacy) return TileHashCache::compute(legacy, kind, l, tile, grid.tile(tile), grid.tileBytes(), fill, sampleBytes);
    return hashes_->get(kind, l, tile, grid.revision(tile), grid.tile(tile), grid.tileBytes(), fill, sampleBytes);
  };
  switch (kind) {
    case hs::terrain::TileKind::Height:
      return hash(terrain_.height.heights(), 0, nullptr, 0);
    case hs::terrain::TileKind::Holes: {
      const uint8_t fill = terrain_.height.holes().fill();
      return hash(terrain_.height.holes(), 0, &fill, sizeof fill);
    }
    case hs::terrain::TileKind::Paint: {
      const uint16_t fill = terrain_.paint.grid(layer).fill();
      return hash(terrain_.paint.grid(layer), layer, &fill, sizeof fill);
    }
  }
  return 0;
}

uint64_t TerrainData::contentHash(TileHashCache::HashFunction legacy) const {
  using hs::terrain::TileKind;
  uint64_t h = 0x5445525241494eull;  // "TERRAIN"
  const int tiles = terrain_.height.heights().tileCount();
  for (int t = 0; t < tiles; ++t) h = hs::terrain::hashCombine(h, tileHash(TileKind::Height, 0, t, legacy));
  for (int t = 0; t < tiles; ++t) h = hs::terrain::hashCombine(h, tileHash(TileKind::Holes, 0, t, legacy));
  for (int l = 0; l < terrain_.paint.layerCount(); ++l)
    for (int t = 0; t < tiles; ++t) h = hs::terrain::hashCombine(h, tileHash(TileKind::Paint, l, t, legacy));
  return h;
}

}  // namespace hs::scene
