// Terrain tile blobs (terrain/tile_blob.h) into a small terrain of 2 x 2
// tiles with two paint layers; the blob's header names the tile.
#include <span>

#include "fuzz_target.h"
#include "terrain/tile_blob.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const hs::terrain::Terrain blank = [] {
    hs::terrain::HeightfieldDesc desc;
    desc.samplesX = desc.samplesY = 257;
    desc.sizeMetres = {256.0, 256.0};
    return std::move(hs::terrain::Terrain::create(desc, {{}, {}}).value());
  }();
  hs::terrain::Terrain t = blank.clone();
  (void)hs::terrain::decodeTile(t, std::span<const uint8_t>(data, size));
  return 0;
}
