#include "mesh/texture_decode.h"

#include <filesystem>
#include <new>

#include "core/image_io.h"
#include "mesh/byte_source.h"

namespace hs::mesh {
namespace {

// Largest texture we accept: 32k x 32k (photogrammetry atlases reach 16k).
constexpr int kMaxTextureSide = 32768;

// Reads an open image into RGBA8, expanding grey/RGB and dropping
// extra channels (said in `note`), converting float/16-bit data to 8-bit.
bool readRgba8(image_io::Reader& in, const std::string& what, Texture& out, std::string& error, std::string* note) {
  const image_io::Spec& spec = in.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxTextureSide ||
      spec.height > kMaxTextureSide) {
    error = what + ": image size " + std::to_string(spec.width) + "x" +
            std::to_string(spec.height) + " is out of range (1 to " +
            std::to_string(kMaxTextureSide) + " per side)";
    return false;
  }
  const int nch = spec.channels;
  if (nch <= 0 || nch > 64) {
    error = what + ": " + std::to_string(nch) + " channels per pixel is out of range (1 to 64)";
    return false;
  }
  // A header may ask for gigabytes (32k x 32k x 64 channels): a failed
  // allocation names the image, not a bare std::bad_alloc.
  std::vector<uint8_t> pixels;
  try {
    pixels.resize(size_t(spec.width) * spec.height * nch);
    out.rgba.reserve(size_t(spec.width) * spec.height * 4);
  } catch (const std::bad_alloc&) {
    error = what + ": image of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " with " +
            std::to_string(nch) + " channels needs more memory than this process may use";
    return false;
  }
  // A decoder may complain and still return true: libjpeg fills a JPEG cut
  // short with grey and only warns ("Premature end of JPEG file"), so
  // anything it said makes the image unreadable, not half grey.
  if (std::string complaint; !in.read(nch, image_io::PixelType::UInt8, pixels.data(), complaint)) {
    error = what + ": cannot decode image: " + (complaint.empty() ? std::string("unknown error") : complaint);
    return false;
  }
  if (nch > 4 && note) {
    std::string names;
    for (size_t c = 0; c < spec.channelNames.size(); ++c) names += (c ? ", " : "") + spec.channelNames[c];
    *note = what + ": " + std::to_string(nch) + " channels" + (names.empty() ? "" : " (" + names + ")") +
            "; drawn from the first 4, the others are kept in the file but not used";
  }
  out.width = spec.width;
  out.height = spec.height;
  out.rgba.resize(size_t(spec.width) * spec.height * 4);
  const size_t n = size_t(spec.width) * spec.height;
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* s = &pixels[i * nch];
    uint8_t* d = &out.rgba[i * 4];
    if (nch == 1) {
      d[0] = d[1] = d[2] = s[0];
      d[3] = 255;
    } else if (nch == 2) {  // grey + alpha
      d[0] = d[1] = d[2] = s[0];
      d[3] = s[1];
    } else {
      d[0] = s[0];
      d[1] = s[1];
      d[2] = s[2];
      d[3] = nch >= 4 ? s[3] : 255;
    }
  }
  return true;
}

}  // namespace

bool decodeTextureFile(const std::string& path, Texture& out, std::string& error, std::string* note) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    error = "texture file not found: " + path;
    return false;
  }
  if (std::filesystem::is_directory(path, ec)) {
    error = "texture path is a directory, not an image: " + path;
    return false;
  }
  // Keep the original bytes: the scene file stores them instead of raw pixels.
  std::vector<uint8_t> bytes;
  if (!readWholeFile(path, bytes, error)) {
    error = "texture " + error;  // "texture a.png: the file changed while it was read (...)"
    return false;
  }
  if (bytes.empty()) {
    error = "texture file is empty (0 bytes): " + path;
    return false;
  }
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  Texture t;
  t.name = std::filesystem::path(path).filename().string();
  if (!decodeTextureMemory(bytes, ext, "texture " + path, t, error, note)) return false;
  t.encoded = std::move(bytes);
  out = std::move(t);
  return true;
}

bool decodeTextureMemory(std::span<const uint8_t> bytes, const std::string& formatHint,
                         const std::string& what, Texture& out, std::string& error, std::string* note) {
  if (bytes.empty()) {
    error = what + ": no image data";
    return false;
  }
  // The file name only tells OpenImageIO which format to try first.
  const std::string pseudoName = "embedded." + (formatHint.empty() ? std::string("png") : formatHint);
  std::string reason;
  auto in = image_io::openMemory(bytes, pseudoName, reason);
  if (!in && image_io::available()) {
    // The hint may be wrong (an embedded JPEG tagged "png"): try the others.
    for (const char* ext : {"png", "jpg", "tga", "bmp", "tif", "exr", "hdr", "webp"}) {
      std::string ignored;
      if ((in = image_io::openMemory(bytes, std::string("embedded.") + ext, ignored))) break;
    }
  }
  if (!in) {
    error = what + ": not a readable image" + (reason.empty() ? "" : " (" + reason + ")");
    return false;
  }
  return readRgba8(*in, what, out, error, note);
}

bool decodeTextureInPlace(Texture& texture, std::string& error) {
  if (texture.encoded.empty()) return !texture.rgba.empty();
  std::string ext = std::filesystem::path(texture.name).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  Texture decoded;
  if (!decodeTextureMemory(texture.encoded, ext, "texture " + texture.name, decoded, error, nullptr))
    return false;
  texture.width = decoded.width;
  texture.height = decoded.height;
  texture.rgba = std::move(decoded.rgba);
  return true;
}

}  // namespace hs::mesh
