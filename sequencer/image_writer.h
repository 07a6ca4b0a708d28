#pragma once
// Writes rendered frames to image files through OpenImageIO, by extension:
// PNG, EXR (half float, linear), JPEG, TIFF. A file appears complete or not
// at all: it is encoded in memory, written under a temporary name beside the
// target and renamed into place, so an interrupted export never leaves a
// half-written frame, and every write error (a full disk, a read-only
// folder) is seen and reported, never hidden in a library's buffered stdio.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"

namespace hs::sequencer {

enum class ImageFormat { Png, Exr, Jpeg, Tiff };

// From the file extension (case-insensitive); nullopt for anything else.
std::optional<ImageFormat> imageFormatFromPath(const std::string& path);
const char* imageFormatName(ImageFormat f);

struct WriteOptions {
  int jpegQuality = 92;   // 1..100
  bool png16 = false;     // 16-bit PNG (from float input)
  // zlib level 0-9. 1 by default, like Blender's default PNG compression
  // (15%): at 3840x1080 it encodes 4.7x faster than zlib's usual 6 for
  // files 6-24% larger (bench/export), and encoding is what bounds a PNG
  // export on two cores.
  int pngCompression = 1;
  std::string description;  // ImageDescription metadata (the export's job tag); "" for none
  // fsync the file before renaming: survives a power cut, costs a disk
  // flush per frame. Off by default: a killed process loses nothing either way.
  bool syncToDisk = false;
};

// The encoded file in memory (no file is touched). False with `error` if
// the image is empty or the encoder fails.
bool encodeImage(ImageFormat format, const ImageView& image, std::vector<uint8_t>& bytes, std::string& error,
                 const WriteOptions& options = {});

// Writes `bytes` to `path` through a temporary name and a rename. False with
// `error` naming the file and the cause: the folder is missing, not
// writable or read-only, or the disk is full ("... disk full: 61440 of
// 812345 bytes written"); the temporary file is removed.
bool writeFileAtomically(const std::string& path, const std::vector<uint8_t>& bytes, std::string& error,
                         bool syncToDisk = false);

// encodeImage + writeFileAtomically, the format from the extension.
bool writeImage(const std::string& path, const ImageView& image, std::string& error,
                const WriteOptions& options = {});

// The temporary name writeFileAtomically uses for `path` (".tmp-<pid>-<name>"),
// and whether a file name is such a temporary name (of any process).
std::string temporaryNameFor(const std::string& path);
bool isTemporaryName(const std::string& fileName, std::string* targetName = nullptr);

}  // namespace hs::sequencer
