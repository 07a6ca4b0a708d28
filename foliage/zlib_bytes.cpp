#include "foliage/zlib_bytes.h"

#include <libdeflate.h>

#include <memory>

namespace hs::foliage {
namespace {

struct Deflater {
  libdeflate_compressor* c;
  explicit Deflater(int level) : c(libdeflate_alloc_compressor(level)) {}
  ~Deflater() { libdeflate_free_compressor(c); }
};
struct Inflater {
  libdeflate_decompressor* d = libdeflate_alloc_decompressor();
  ~Inflater() { libdeflate_free_decompressor(d); }
};

}  // namespace

std::vector<uint8_t> deflateBytes(const uint8_t* bytes, size_t size, int level) {
  thread_local std::unique_ptr<Deflater> deflater;
  thread_local int deflaterLevel = -1;
  if (!deflater || deflaterLevel != level) {
    deflater = std::make_unique<Deflater>(level);
    deflaterLevel = level;
  }
  std::vector<uint8_t> out(libdeflate_zlib_compress_bound(deflater->c, size));
  out.resize(libdeflate_zlib_compress(deflater->c, bytes, size, out.data(), out.size()));
  return out;
}

bool inflateBytes(const uint8_t* bytes, size_t size, uint8_t* out, size_t outSize) {
  thread_local Inflater inflater;
  size_t got = 0;
  return libdeflate_zlib_decompress(inflater.d, bytes, size, out, outSize, &got) == LIBDEFLATE_SUCCESS &&
         got == outSize;
}

}  // namespace hs::foliage
