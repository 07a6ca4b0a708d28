#include "sequencer/image_writer.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "core/image_io.h"
#include "core/srgb.h"

namespace hs::sequencer {

namespace fs = std::filesystem;

std::optional<ImageFormat> imageFormatFromPath(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".png") return ImageFormat::Png;
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::Jpeg;
  if (ext == ".tif" || ext == ".tiff") return ImageFormat::Tiff;
  return std::nullopt;
}

const char* imageFormatName(ImageFormat f) {
  switch (f) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Exr: return "EXR";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::Tiff: return "TIFF";
  }
  return "?";
}

namespace {

const char* oiioFormatName(ImageFormat f) {
  switch (f) {
    case ImageFormat::Png: return "png";
    case ImageFormat::Exr: return "openexr";
    case ImageFormat::Jpeg: return "jpeg";
    case ImageFormat::Tiff: return "tiff";
  }
  return "png";
}

}  // namespace

bool encodeImage(ImageFormat format, const ImageView& img, std::vector<uint8_t>& bytes, std::string& error,
                 const WriteOptions& options) {
  if (img.width <= 0 || img.height <= 0 || (!img.rgba8 && !img.rgbaF)) {
    error = "no image to write";
    return false;
  }
  // Pixel data in the form the format wants.
  const size_t n = size_t(img.width) * size_t(img.height);
  image_io::Spec spec;
  spec.width = img.width, spec.height = img.height;
  std::vector<uint8_t> bytes8;
  std::vector<uint16_t> bytes16;
  std::vector<float> floats;
  const void* pixels = nullptr;
  image_io::PixelType memoryType = image_io::PixelType::UInt8;  // what `pixels` holds; converted to spec.format
  if (format == ImageFormat::Exr) {
    // Linear RGBA half float; sRGB input is decoded.
    spec.channels = 4, spec.format = image_io::PixelType::Half;
    if (img.rgbaF) {
      pixels = img.rgbaF;
    } else {
      floats.resize(n * 4);
      for (size_t i = 0; i < n * 4; ++i)
        floats[i] = (i % 4) == 3 ? float(img.rgba8[i]) / 255.0f : srgb8ToLinear(img.rgba8[i]);
      pixels = floats.data();
    }
    memoryType = image_io::PixelType::Float;
    spec.text.emplace_back("compression", "zip");
  } else if (format == ImageFormat::Png && options.png16) {
    spec.channels = 3, spec.format = image_io::PixelType::UInt16;
    bytes16.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const float v = img.rgbaF ? linearToSrgbFloat(img.rgbaF[i * 4 + size_t(c)])
                                  : float(img.rgba8[i * 4 + size_t(c)]) / 255.0f;
        bytes16[i * 3 + size_t(c)] = uint16_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f));
      }
    pixels = bytes16.data();
    memoryType = image_io::PixelType::UInt16;
  } else {
    // 8-bit sRGB RGB: frames are opaque, and JPEG has no alpha anyway.
    spec.channels = 3, spec.format = image_io::PixelType::UInt8;
    bytes8.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        bytes8[i * 3 + size_t(c)] = img.rgba8 ? img.rgba8[i * 4 + size_t(c)] : linearToSrgb8(img.rgbaF[i * 4 + size_t(c)]);
    pixels = bytes8.data();
    if (format == ImageFormat::Jpeg) spec.ints.emplace_back("CompressionQuality", std::clamp(options.jpegQuality, 1, 100));
    if (format == ImageFormat::Tiff) spec.text.emplace_back("compression", "zip");
    // sRGB is what 8-bit PNG/JPEG/TIFF mean anyway. Not for TIFF: OIIO 2.4
    // then writes an extra directory that breaks the file when it encodes
    // to memory ("missing required ImageLength").
    if (format != ImageFormat::Tiff) spec.text.emplace_back("oiio:ColorSpace", "sRGB");
  }
  if (format == ImageFormat::Png) spec.ints.emplace_back("png:compressionLevel", std::clamp(options.pngCompression, 0, 9));
  if (!options.description.empty()) spec.text.emplace_back("ImageDescription", options.description);

  if (std::string why; !image_io::encode(oiioFormatName(format), spec, memoryType, pixels, bytes, why)) {
    error = std::string("encoding ") + imageFormatName(format) + " failed: " + why;
    return false;
  }
  return true;
}

std::string temporaryNameFor(const std::string& path) {
  const fs::path target(path);
  return (target.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string())).string();
}

bool isTemporaryName(const std::string& name, std::string* targetName) {
  if (name.rfind(".tmp-", 0) != 0) return false;
  size_t i = 5;
  while (i < name.size() && name[i] >= '0' && name[i] <= '9') ++i;
  if (i == 5 || i >= name.size() || name[i] != '-') return false;
  if (targetName) *targetName = name.substr(i + 1);
  return true;
}

namespace {

std::string describeErrno(int err, const fs::path& dir) {
  const std::string where = dir.empty() ? std::string("the current folder") : dir.string();
  switch (err) {
    case ENOSPC: return "disk full in " + where + " (" + std::strerror(err) + ")";
    case EDQUOT: return "disk quota exceeded in " + where;
    case EACCES:
    case EPERM: return "folder " + where + " is not writable (" + std::strerror(err) + ")";
    case EROFS: return "folder " + where + " is on a read-only file system";
    case ENOENT: return "folder " + where + " does not exist";
    default: return std::strerror(err);
  }
}

}  // namespace

bool writeFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes, std::string& error,
                         bool syncToDisk) {
  const fs::path target(path);
  const fs::path dir = target.parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec)) {
    error = path + ": folder " + dir.string() + " does not exist";
    return false;
  }
  const std::string tmp = temporaryNameFor(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = path + ": cannot write: " + describeErrno(errno, dir);
    return false;
  }
  size_t done = 0;
  int err = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (w < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    done += size_t(w);
  }
  if (!err && syncToDisk && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && !err) err = errno;  // NFS reports a full disk at close
  if (err) {
    fs::remove(tmp, ec);
    error = path + ": cannot write: " + describeErrno(err, dir) + ": " + std::to_string(done) + " of " +
            std::to_string(bytes.size()) + " bytes written";
    return false;
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    error = path + ": cannot move the finished file into place: " + ec.message();
    return false;
  }
  return true;
}

bool writeImage(const std::string& path, const ImageView& img, std::string& error, const WriteOptions& options) {
  const auto format = imageFormatFromPath(path);
  if (!format) {
    error = path + ": unknown image type; use .png, .exr, .jpg or .tif";
    return false;
  }
  std::vector<uint8_t> bytes;
  if (!encodeImage(*format, img, bytes, error, options)) {
    error = path + ": " + error;
    return false;
  }
  return writeFileAtomically(path, bytes, error, options.syncToDisk);
}

}  // namespace hs::sequencer
