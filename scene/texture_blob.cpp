#include "scene/texture_blob.h"

#include <cstring>

#include "core/content_hash.h"
#include "mesh/texture_decode.h"

namespace hs::scene {
namespace {

constexpr char kMagic[8] = {'H', 'S', 'T', 'E', 'X', '0', '0', '1'};

struct Header {
  char magic[8];
  int32_t width;
  int32_t height;
  uint32_t encoded;  // 1: the bytes are the source file's; 0: RGBA8
  uint32_t nameBytes;
  uint64_t dataBytes;
};

}  // namespace

std::vector<uint8_t> encodeTexture(const mesh::Texture& t) {
  const bool encoded = !t.encoded.empty();
  const std::vector<uint8_t>& data = encoded ? t.encoded : t.rgba;
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.width = t.width;
  h.height = t.height;
  h.encoded = encoded ? 1 : 0;
  h.nameBytes = uint32_t(t.name.size());
  h.dataBytes = data.size();
  std::vector<uint8_t> out(sizeof h + t.name.size() + data.size());
  std::memcpy(out.data(), &h, sizeof h);
  std::memcpy(out.data() + sizeof h, t.name.data(), t.name.size());
  if (!data.empty()) std::memcpy(out.data() + sizeof h + t.name.size(), data.data(), data.size());
  return out;
}

std::optional<mesh::Texture> decodeTexture(const uint8_t* data, size_t size, const std::string& what,
                                           std::string& error) {
  Header h{};
  if (size < sizeof h) {
    error = what + ": its data is cut short (" + std::to_string(size) + " bytes)";
    return std::nullopt;
  }
  std::memcpy(&h, data, sizeof h);
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0) {
    error = what + ": its data is not a texture (damaged file)";
    return std::nullopt;
  }
  if (uint64_t(sizeof h) + h.nameBytes + h.dataBytes != size) {
    error = what + ": its data has " + std::to_string(size) + " bytes where its header says " +
            std::to_string(sizeof h + h.nameBytes + h.dataBytes) + " (damaged file)";
    return std::nullopt;
  }
  mesh::Texture t;
  t.name.assign(reinterpret_cast<const char*>(data + sizeof h), h.nameBytes);
  const uint8_t* bytes = data + sizeof h + h.nameBytes;
  if (h.encoded) {
    t.encoded.assign(bytes, bytes + h.dataBytes);
    std::string e;
    if (!mesh::decodeTextureInPlace(t, e)) {
      error = what + ": " + e;
      return std::nullopt;
    }
    return t;
  }
  if (h.width <= 0 || h.height <= 0 || uint64_t(h.width) * uint64_t(h.height) * 4 != h.dataBytes) {
    error = what + ": its size " + std::to_string(h.width) + "x" + std::to_string(h.height) + " does not match its " +
            std::to_string(h.dataBytes) + " bytes of RGBA (damaged file)";
    return std::nullopt;
  }
  t.width = h.width;
  t.height = h.height;
  t.rgba.assign(bytes, bytes + h.dataBytes);
  return t;
}

uint64_t textureContentHash(const mesh::Texture& t) {
  ContentHasher h;
  h.value(int32_t(t.width)).value(int32_t(t.height)).array(t.rgba);
  return h.digest();
}

}  // namespace hs::scene
