#include "terrain/tile_blob.h"

#include <bit>
#include <cstring>
#include <memory>

// libdeflate, not zlib: the same zlib streams GDAL's CPLZLibDeflate wrote
// here before (GDAL 3.6 uses libdeflate for it; byte for byte the same at
// level 6, so a saved terrain's blobs do not change), without linking GDAL
// for two calls (terrain/gdal_door.h says why GDAL is loaded only when
// needed).
#include <libdeflate.h>

namespace hs::terrain {
namespace {

static_assert(std::endian::native == std::endian::little, "tile blobs are written little endian");

constexpr uint16_t kVersion = 1;
constexpr size_t kHeaderBytes = 4 + 2 + 1 + 1 + 2 + 2 + 4 + 4 + 4 + 8;
constexpr uint8_t kUniform = 1, kDeflate = 2;

template <class T>
void put(uint8_t*& p, T v) {
  std::memcpy(p, &v, sizeof(T));
  p += sizeof(T);
}
template <class T>
T get(const uint8_t*& p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  p += sizeof(T);
  return v;
}

struct CompressorFree {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
struct DecompressorFree {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

// A zlib stream of `in` at level 6 into `out`; its size, or 0 when it does
// not fit. One compressor per thread: allocating one costs more than
// compressing a tile.
size_t deflateZlib(std::span<const uint8_t> in, std::span<uint8_t> out) {
  thread_local std::unique_ptr<libdeflate_compressor, CompressorFree> c(libdeflate_alloc_compressor(6));
  return c ? libdeflate_zlib_compress(c.get(), in.data(), in.size(), out.data(), out.size()) : 0;
}

// Inflates a zlib stream that must fill `out` exactly.
bool inflateZlib(std::span<const uint8_t> in, std::span<uint8_t> out) {
  thread_local std::unique_ptr<libdeflate_decompressor, DecompressorFree> d(libdeflate_alloc_decompressor());
  size_t got = 0;
  return d && libdeflate_zlib_decompress(d.get(), in.data(), in.size(), out.data(), out.size(), &got) ==
                  LIBDEFLATE_SUCCESS &&
         got == out.size();
}

template <class T>
std::vector<uint8_t> encode(TileKind kind, int tile, int layer, const T* data, T fill) {
  std::vector<uint8_t> payload;
  uint8_t flags = 0;
  bool uniform = true;
  const T first = data ? data[0] : fill;
  if (data)
    for (int i = 1; i < kTileSamples && uniform; ++i) uniform = std::memcmp(&data[i], &first, sizeof(T)) == 0;
  if (uniform) {
    flags |= kUniform;
    payload.resize(sizeof(T));
    std::memcpy(payload.data(), &first, sizeof(T));
  } else {
    // Byte planes first (all low bytes, then the next, ...): neighbouring
    // heights share their high bytes, which deflate then finds.
    std::vector<uint8_t> planes(sizeof(T) * kTileSamples);
    const uint8_t* src = reinterpret_cast<const uint8_t*>(data);
    for (int i = 0; i < kTileSamples; ++i)
      for (size_t b = 0; b < sizeof(T); ++b) planes[b * kTileSamples + size_t(i)] = src[size_t(i) * sizeof(T) + b];
    payload.resize(planes.size() + 1024);
    const size_t outBytes = deflateZlib(planes, payload);
    if (outBytes > 0 && outBytes < planes.size()) {
      payload.resize(outBytes);
      flags |= kDeflate;
    } else {
      payload.assign(src, src + sizeof(T) * kTileSamples);
    }
  }
  // Fixed-offset header written with memcpy (no vector growth to confuse
  // GCC 12's -Wstringop-overflow).
  std::vector<uint8_t> out(kHeaderBytes + payload.size());
  uint8_t* p = out.data();
  std::memcpy(p, "HSTT", 4);
  p += 4;
  put<uint16_t>(p, kVersion);
  put<uint8_t>(p, uint8_t(kind));
  put<uint8_t>(p, flags);
  put<uint16_t>(p, uint16_t(kTileSize));
  put<uint16_t>(p, 0);
  put<uint32_t>(p, uint32_t(tile));
  put<uint32_t>(p, uint32_t(layer));
  put<uint32_t>(p, uint32_t(payload.size()));
  put<uint64_t>(p, fnv1a(payload));
  if (!payload.empty()) std::memcpy(p, payload.data(), payload.size());
  return out;
}

template <class T>
Status decodeInto(TileGrid<T>& grid, int tile, uint8_t flags, std::span<const uint8_t> payload, const std::string& what,
                  bool dense) {
  if (flags & kUniform) {
    if (payload.size() != sizeof(T)) return Status::failure(what + ": uniform tile payload has the wrong size");
    T v;
    std::memcpy(&v, payload.data(), sizeof(T));
    if (v == grid.fill() && !dense) {
      grid.setTile(tile, nullptr);
      return {};
    }
    typename TileGrid<T>::TilePtr p(new T[kTileSamples]);
    std::fill(p.get(), p.get() + kTileSamples, v);
    grid.setTile(tile, std::move(p));
    return {};
  }
  std::vector<uint8_t> raw(sizeof(T) * kTileSamples);
  if (flags & kDeflate) {
    std::vector<uint8_t> planes(raw.size());
    if (!inflateZlib(payload, planes))
      return Status::failure(what + ": compressed tile data is damaged");
    for (int i = 0; i < kTileSamples; ++i)
      for (size_t b = 0; b < sizeof(T); ++b) raw[size_t(i) * sizeof(T) + b] = planes[b * kTileSamples + size_t(i)];
  } else {
    if (payload.size() != raw.size()) return Status::failure(what + ": tile payload has the wrong size");
    std::memcpy(raw.data(), payload.data(), raw.size());
  }
  typename TileGrid<T>::TilePtr p(new T[kTileSamples]);
  std::memcpy(p.get(), raw.data(), raw.size());
  grid.setTile(tile, std::move(p));
  return {};
}

}  // namespace

uint64_t fnv1a(std::span<const uint8_t> bytes) {
  uint64_t h = 1469598103934665603ull;
  for (uint8_t b : bytes) {
    h ^= b;
    h *= 1099511628211ull;
  }
  return h;
}

std::vector<uint8_t> encodeHeightTile(const Heightfield& hf, int tile) {
  return encode<float>(TileKind::Height, tile, 0, hf.heights().tile(tile), hf.heights().fill());
}
std::vector<uint8_t> encodeHolesTile(const Heightfield& hf, int tile) {
  return encode<uint8_t>(TileKind::Holes, tile, 0, hf.holes().tile(tile), hf.holes().fill());
}
std::vector<uint8_t> encodePaintTile(const PaintLayers& paint, int layer, int tile) {
  return encode<uint16_t>(TileKind::Paint, tile, layer, paint.grid(layer).tile(tile), paint.grid(layer).fill());
}

Status decodeTile(Terrain& terrain, std::span<const uint8_t> blob) {
  if (blob.size() < kHeaderBytes || std::memcmp(blob.data(), "HSTT", 4) != 0)
    return Status::failure("terrain tile blob: not a terrain tile (bad header)");
  const uint8_t* p = blob.data() + 4;
  const uint16_t version = get<uint16_t>(p);
  const uint8_t kind = get<uint8_t>(p), flags = get<uint8_t>(p);
  const uint16_t tileSize = get<uint16_t>(p);
  get<uint16_t>(p);
  const uint32_t tile = get<uint32_t>(p), layer = get<uint32_t>(p), size = get<uint32_t>(p);
  const uint64_t sum = get<uint64_t>(p);
  const std::string what = "terrain tile " + std::to_string(tile);
  if (version != kVersion)
    return Status::failure(what + ": format version " + std::to_string(version) + " is newer than this build reads");
  if (tileSize != kTileSize) return Status::failure(what + ": tile size " + std::to_string(tileSize) + " is not 128");
  if (blob.size() != kHeaderBytes + size) return Status::failure(what + ": blob is truncated or has trailing bytes");
  const std::span<const uint8_t> payload = blob.subspan(kHeaderBytes);
  if (fnv1a(payload) != sum) return Status::failure(what + ": checksum mismatch (damaged data)");
  if (int64_t(tile) >= terrain.height.heights().tileCount())
    return Status::failure(what + ": index outside this terrain's " +
                           std::to_string(terrain.height.heights().tileCount()) + " tiles");
  switch (TileKind(kind)) {
    case TileKind::Height: {
      Status s = decodeInto(terrain.height.heights(), int(tile), flags, payload, what, true);
      if (s) terrain.height.updateBounds(terrain.height.heights().tileRegion(int(tile)));
      return s;
    }
    case TileKind::Holes: return decodeInto(terrain.height.holes(), int(tile), flags, payload, what, false);
    case TileKind::Paint:
      if (int64_t(layer) >= terrain.paint.layerCount())
        return Status::failure(what + ": paint layer " + std::to_string(layer) + " does not exist");
      return decodeInto(terrain.paint.grid(int(layer)), int(tile), flags, payload, what, false);
  }
  return Status::failure(what + ": unknown tile kind " + std::to_string(kind));
}

std::string tileBlobKey(TileKind kind, int layer, int tx, int ty) {
  const std::string xy = std::to_string(tx) + "_" + std::to_string(ty);
  switch (kind) {
    case TileKind::Height: return "height/" + xy;
    case TileKind::Holes: return "holes/" + xy;
    case TileKind::Paint: return "paint/" + std::to_string(layer) + "/" + xy;
  }
  return xy;
}

TerrainRevisions currentRevisions(const Terrain& t) {
  TerrainRevisions r;
  r.heights = t.height.heights().revisionCounter();
  r.holes = t.height.holes().revisionCounter();
  for (int l = 0; l < t.paint.layerCount(); ++l) r.paint.push_back(t.paint.grid(l).revisionCounter());
  return r;
}

DirtyTiles tilesChangedSince(const Terrain& t, const TerrainRevisions& saved) {
  DirtyTiles d;
  d.heights = t.height.heights().tilesChangedSince(saved.heights);
  d.holes = t.height.holes().tilesChangedSince(saved.holes);
  for (int l = 0; l < t.paint.layerCount(); ++l) {
    const uint64_t since = size_t(l) < saved.paint.size() ? saved.paint[size_t(l)] : 0;
    for (int tile : t.paint.grid(l).tilesChangedSince(since)) d.paint.emplace_back(l, tile);
  }
  return d;
}

}  // namespace hs::terrain
