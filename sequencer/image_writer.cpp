#include "sequencer/image_writer.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

namespace hs::sequencer {

std::optional<ImageFormat> imageFormatFromPath(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
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

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

bool writeImage(const std::string& path, const ImageView& img, std::string& error, const WriteOptions& options) {
  namespace fs = std::filesystem;
  const auto format = imageFormatFromPath(path);
  if (!format) {
    error = path + ": unknown image type; use .png, .exr, .jpg or .tif";
    return false;
  }
  if (img.width <= 0 || img.height <= 0 || (!img.rgba8 && !img.rgbaF)) {
    error = path + ": no image to write";
    return false;
  }
  const fs::path dir = fs::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec)) {
    error = path + ": folder " + dir.string() + " does not exist";
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
  if (*format == ImageFormat::Exr) {
    // Linear RGBA half float; sRGB input is decoded.
    spec = OIIO::ImageSpec(img.width, img.height, 4, OIIO::TypeDesc::HALF);
    floats.resize(n * 4);
    for (size_t i = 0; i < n * 4; ++i)
      floats[i] = img.rgbaF ? img.rgbaF[i]
                            : ((i % 4) == 3 ? float(img.rgba8[i]) / 255.0f : srgbToLinear(float(img.rgba8[i]) / 255.0f));
    pixels = floats.data();
    memoryType = OIIO::TypeDesc::FLOAT;
  } else if (*format == ImageFormat::Png && options.png16) {
    spec = OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::UINT16);
    bytes16.resize(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const float v = img.rgbaF ? linearToSrgb(img.rgbaF[i * 4 + size_t(c)]) : float(img.rgba8[i * 4 + size_t(c)]) / 255.0f;
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
        bytes8[i * 3 + size_t(c)] = img.rgba8 ? img.rgba8[i * 4 + size_t(c)]
                                              : uint8_t(std::lround(linearToSrgb(img.rgbaF[i * 4 + size_t(c)]) * 255.0f));
    pixels = bytes8.data();
    if (*format == ImageFormat::Jpeg) spec.attribute("CompressionQuality", std::clamp(options.jpegQuality, 1, 100));
    spec.attribute("oiio:ColorSpace", "sRGB");
  }
  if (*format == ImageFormat::Exr) spec.attribute("compression", "zip");
  if (*format == ImageFormat::Tiff) spec.attribute("compression", "zip");

  // Temporary name with the same extension (OIIO picks the writer by it).
  const fs::path target(path);
  const fs::path tmp = target.parent_path() /
                       (".tmp-" + std::to_string(::getpid()) + "-" + target.filename().string());
  {
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out) {
      error = path + ": no writer for this image type (" + OIIO::geterror() + ")";
      return false;
    }
    if (!out->open(tmp.string(), spec) || !out->write_image(memoryType, pixels) || !out->close()) {
      std::string why = out->geterror();
      fs::remove(tmp, ec);
      if (why.empty()) why = "write failed (disk full or folder not writable?)";
      error = path + ": cannot write: " + why;
      return false;
    }
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    error = path + ": cannot move the finished image into place: " + ec.message();
    return false;
  }
  return true;
}

}  // namespace hs::sequencer
