#include "sequencer/image_writer.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

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

// An in-memory file for OpenImageIO writers: unlike OIIO's IOVecOutput it
// reads back and seeks anywhere, which libtiff needs to write its directory
// (with IOVecOutput OIIO 2.4 writes TIFFs without their ImageLength).
class MemoryFile final : public OIIO::Filesystem::IOProxy {
 public:
  explicit MemoryFile(std::vector<uint8_t>& bytes) : IOProxy("", Write), bytes_(bytes) {}
  const char* proxytype() const override { return "hs-memory"; }
  size_t read(void* buf, size_t size) override {
    const size_t n = pread(buf, size, m_pos);
    m_pos += int64_t(n);
    return n;
  }
  size_t write(const void* buf, size_t size) override {
    const size_t n = pwrite(buf, size, m_pos);
    m_pos += int64_t(n);
    return n;
  }
  size_t pread(void* buf, size_t size, int64_t offset) override {
    if (offset < 0 || size_t(offset) >= bytes_.size()) return 0;
    const size_t n = std::min(size, bytes_.size() - size_t(offset));
    std::memcpy(buf, bytes_.data() + offset, n);
    return n;
  }
  size_t pwrite(const void* buf, size_t size, int64_t offset) override {
    if (offset < 0) return 0;
    if (bytes_.size() < size_t(offset) + size) bytes_.resize(size_t(offset) + size);
    std::memcpy(bytes_.data() + offset, buf, size);
    return size;
  }
  size_t size() const override { return bytes_.size(); }

 private:
  std::vector<uint8_t>& bytes_;
};

}  // namespace

bool encodeImage(ImageFormat format, const ImageView& img, std::vector<uint8_t>& bytes, std::string& error,
                 const WriteOptions& options) {
  if (img.width <= 0 || img.height <= 0 || (!img.rgba8 && !img.rgbaF)) {
    error = "no image to write";
    return false;
  }
  // Pixel data in the form the format wants.
  const size_t n = size_t(img.width) * size_t(img.height);
  OIIO::ImageSpec spec;
  std::vector<uint8_t> bytes8;
  std::vector<uint16_t> bytes16;
  std::vector<float> floats;
  const void* pixels = nullptr;
  OIIO::TypeDesc memoryType = OIIO::TypeDesc::UINT8;  // what `pixels` holds; OIIO converts to spec.format
  if (format == ImageFormat::Exr) {
    // Linear RGBA half float; sRGB input is decoded.
    spec = OIIO::ImageSpec(img.width, img.height, 4, OIIO::TypeDesc::HALF);
    if (img.rgbaF) {
      pixels = img.rgbaF;
    } else {
      floats.resize(n * 4);
      for (size_t i = 0; i < n * 4; ++i)
        floats[i] = (i % 4) == 3 ? float(img.rgba8[i]) / 255.0f : srgb8ToLinear(img.rgba8[i]);
      pixels = floats.data();
    }
    memoryType = OIIO::TypeDesc::FLOAT;
    spec.attribute("compression", "zip");
  } else if (format == ImageFormat::Png && options.png16) {
    spec = OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::UINT16);
    bytes16.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const float v = img.rgbaF ? linearToSrgbFloat(img.rgbaF[i * 4 + size_t(c)])
                                  : float(img.rgba8[i * 4 + size_t(c)]) / 255.0f;
        bytes16[i * 3 + size_t(c)] = uint16_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f));
      }
    pixels = bytes16.data();
    memoryType = OIIO::TypeDesc::UINT16;
  } else {
    // 8-bit sRGB RGB: frames are opaque, and JPEG has no alpha anyway.
    spec = OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
    bytes8.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        bytes8[i * 3 + size_t(c)] = img.rgba8 ? img.rgba8[i * 4 + size_t(c)] : linearToSrgb8(img.rgbaF[i * 4 + size_t(c)]);
    pixels = bytes8.data();
    if (format == ImageFormat::Jpeg) spec.attribute("CompressionQuality", std::clamp(options.jpegQuality, 1, 100));
    if (format == ImageFormat::Tiff) spec.attribute("compression", "zip");
    // sRGB is what 8-bit PNG/JPEG/TIFF mean anyway. Not for TIFF: OIIO 2.4
    // then writes an extra directory that breaks the file when it encodes
    // to memory ("missing required ImageLength").
    if (format != ImageFormat::Tiff) spec.attribute("oiio:ColorSpace", "sRGB");
  }
  if (format == ImageFormat::Png) spec.attribute("png:compressionLevel", std::clamp(options.pngCompression, 0, 9));
  if (!options.description.empty()) spec.attribute("ImageDescription", options.description);

  bytes.clear();
  MemoryFile proxy(bytes);
  auto out = OIIO::ImageOutput::create(oiioFormatName(format));
  if (!out) {
    error = std::string("no ") + imageFormatName(format) + " writer (" + OIIO::geterror() + ")";
    return false;
  }
  if (!out->supports("ioproxy") || !out->set_ioproxy(&proxy)) {
    error = std::string("the ") + imageFormatName(format) + " writer cannot encode to memory";
    return false;
  }
  const std::string nominal = std::string("frame.") + oiioFormatName(format);
  if (!out->open(nominal, spec) || !out->write_image(memoryType, pixels) || !out->close()) {
    error = std::string("encoding ") + imageFormatName(format) + " failed: " + out->geterror();
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
