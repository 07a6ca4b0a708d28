#pragma once
// zlib streams through libdeflate (faster than zlib's own at equal ratio),
// for the foliage's blobs: cells (store.h) and impostor atlases
// (impostor_images.h). One compressor per thread and level, kept.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hs::foliage {

// `bytes` as a zlib stream; `level` is libdeflate's (1 fastest .. 12).
std::vector<uint8_t> deflateBytes(const uint8_t* bytes, size_t size, int level);
// Inflates `size` bytes of a zlib stream into exactly `outSize` bytes at
// `out`. False when the stream is corrupt or does not give that many.
bool inflateBytes(const uint8_t* bytes, size_t size, uint8_t* out, size_t outSize);

}  // namespace hs::foliage
