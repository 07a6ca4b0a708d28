#pragma once
// Writes rendered frames to image files through OpenImageIO, by extension:
// PNG, EXR (half float, linear), JPEG, TIFF. A file appears complete or not
// at all: it is written under a temporary name and renamed into place, so an
// interrupted export never leaves a half-written frame.
#include <cstdint>
#include <optional>
#include <string>

namespace hs::sequencer {

enum class ImageFormat { Png, Exr, Jpeg, Tiff };

// From the file extension (case-insensitive); nullopt for anything else.
std::optional<ImageFormat> imageFormatFromPath(const std::string& path);
const char* imageFormatName(ImageFormat f);

struct ImageView {
  int width = 0;
  int height = 0;
  const uint8_t* rgba8 = nullptr;  // sRGB display pixels, top row first, or
  const float* rgbaF = nullptr;    // linear HDR pixels, top row first
};

struct WriteOptions {
  int jpegQuality = 92;   // 1..100
  bool png16 = false;     // 16-bit PNG (from float input)
};

// False with `error` naming the file (and why: unknown extension, folder
// missing or not writable, disk full) on failure; nothing is left behind.
bool writeImage(const std::string& path, const ImageView& image, std::string& error,
                const WriteOptions& options = {});

}  // namespace hs::sequencer
