#include "foliage/impostor_images.h"

#include <cmath>

#include "core/content_hash.h"
#include "foliage/byte_io.h"
#include "foliage/zlib_bytes.h"

namespace hs::foliage {
namespace {

constexpr uint32_t kMagic = 0x4D495348u;  // "HSIM"
constexpr size_t kHeaderBytes = 52;
constexpr int kMaxFrames = 64, kMaxFramePixels = 1024, kMaxSide = 8192;

using byte_io::get;
using byte_io::put;

// Both images, each channel a plane, each byte less its left neighbour in
// its row (the first of a row kept): the filter named in the header.
std::vector<uint8_t> filtered(const ImpostorImages& im) {
  const size_t side = size_t(im.side()), pixels = side * side;
  std::vector<uint8_t> out(2 * pixels * 4);
  size_t o = 0;
  for (const std::vector<uint8_t>* img : {&im.albedo, &im.normalDepth})
    for (size_t c = 0; c < 4; ++c)
      for (size_t y = 0; y < side; ++y) {
        const uint8_t* row = img->data() + y * side * 4 + c;
        uint8_t prev = 0;
        for (size_t x = 0; x < side; ++x) {
          const uint8_t v = row[x * 4];
          out[o++] = uint8_t(v - prev);
          prev = v;
        }
      }
  return out;
}

void unfilter(const std::vector<uint8_t>& raw, ImpostorImages& im) {
  const size_t side = size_t(im.side()), pixels = side * side;
  im.albedo.assign(pixels * 4, 0);
  im.normalDepth.assign(pixels * 4, 0);
  size_t i = 0;
  for (std::vector<uint8_t>* img : {&im.albedo, &im.normalDepth})
    for (size_t c = 0; c < 4; ++c)
      for (size_t y = 0; y < side; ++y) {
        uint8_t* row = img->data() + y * side * 4 + c;
        uint8_t prev = 0;
        for (size_t x = 0; x < side; ++x) {
          prev = uint8_t(prev + raw[i++]);
          row[x * 4] = prev;
        }
      }
}

}  // namespace

uint64_t ImpostorImages::contentHash() const {
  const uint64_t h = hs::contentHash(albedo.data(), albedo.size(), uint64_t(frames) << 16 | uint64_t(framePixels));
  return hs::contentHash(normalDepth.data(), normalDepth.size(), h);
}

std::vector<uint8_t> encodeImpostor(const ImpostorImages& im, int level) {
  const std::vector<uint8_t> raw = filtered(im);
  const std::vector<uint8_t> payload = deflateBytes(raw.data(), raw.size(), level);
  std::vector<uint8_t> out;
  out.reserve(kHeaderBytes + payload.size());
  put<uint32_t>(out, kMagic);
  put<uint16_t>(out, 1);
  put<uint16_t>(out, uint16_t(im.frames));
  put<uint16_t>(out, uint16_t(im.framePixels));
  put<uint16_t>(out, 0);
  for (int k = 0; k < 4; ++k) put<float>(out, im.sphere[k]);
  put<uint64_t>(out, im.sourceKey);
  put<uint32_t>(out, uint32_t(raw.size()));
  put<uint32_t>(out, uint32_t(payload.size()));
  put<uint64_t>(out, im.contentHash());
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

std::optional<ImpostorImages> decodeImpostor(std::span<const uint8_t> blob, const std::string& what,
                                             std::string& error) {
  auto fail = [&](size_t offset, const std::string& why) {
    error = what + ": byte offset " + std::to_string(offset) + ": " + why;
    return std::nullopt;
  };
  if (blob.size() < kHeaderBytes)
    return fail(blob.size(), "truncated: the blob has " + std::to_string(blob.size()) + " bytes, its header needs " +
                                 std::to_string(kHeaderBytes));
  const uint8_t* b = blob.data();
  if (get<uint32_t>(b) != kMagic) return fail(0, "not an impostor blob (no \"HSIM\" signature)");
  if (get<uint16_t>(b + 4) != 1)
    return fail(4, "format version " + std::to_string(get<uint16_t>(b + 4)) + " is not one this build reads (1)");
  ImpostorImages im;
  im.frames = get<uint16_t>(b + 6);
  im.framePixels = get<uint16_t>(b + 8);
  if (im.frames < 1 || im.frames > kMaxFrames)
    return fail(6, std::to_string(im.frames) + " frames a side (1 to " + std::to_string(kMaxFrames) + " are read)");
  if (im.framePixels < 1 || im.framePixels > kMaxFramePixels || im.side() > kMaxSide)
    return fail(8, std::to_string(im.framePixels) + " pixels a frame side with " + std::to_string(im.frames) +
                       " frames (up to " + std::to_string(kMaxFramePixels) + " a frame and " +
                       std::to_string(kMaxSide) + " an atlas are read)");
  for (int k = 0; k < 4; ++k) im.sphere[k] = get<float>(b + 12 + 4 * k);
  if (!std::isfinite(im.sphere.x) || !std::isfinite(im.sphere.y) || !std::isfinite(im.sphere.z) ||
      !(im.sphere.w > 0.0f) || !std::isfinite(im.sphere.w))
    return fail(12, "the bounding sphere is not finite with a positive radius");
  im.sourceKey = get<uint64_t>(b + 28);
  const size_t rawBytes = get<uint32_t>(b + 36), payload = get<uint32_t>(b + 40);
  const uint64_t hash = get<uint64_t>(b + 44);
  if (rawBytes != 2 * im.imageBytes())
    return fail(36, "raw size " + std::to_string(rawBytes) + " is not two " + std::to_string(im.side()) + " x " +
                        std::to_string(im.side()) + " RGBA8 images (" + std::to_string(2 * im.imageBytes()) + ")");
  if (blob.size() < kHeaderBytes + payload)
    return fail(blob.size(), "truncated: the header declares " + std::to_string(payload) + " payload bytes from byte " +
                                 "offset " + std::to_string(kHeaderBytes) + ", the blob ends after " +
                                 std::to_string(blob.size() - kHeaderBytes));
  if (blob.size() > kHeaderBytes + payload)
    return fail(kHeaderBytes + payload,
                std::to_string(blob.size() - kHeaderBytes - payload) + " bytes after the payload's end");
  std::vector<uint8_t> raw(rawBytes);
  if (!inflateBytes(b + kHeaderBytes, payload, raw.data(), raw.size()))
    return fail(kHeaderBytes, "the compressed payload is corrupt or of the wrong size");
  unfilter(raw, im);
  if (im.contentHash() != hash)
    return fail(44, "content hash mismatch (stored " + toHex(hash) + ", the images hash to " + toHex(im.contentHash()) +
                        ")");
  return im;
}

}  // namespace hs::foliage
