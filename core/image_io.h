#pragma once
// Image files (PNG, EXR, JPEG, TIFF and whatever else OpenImageIO reads):
// the one door every library goes through to read or write one.
//
// Why a door and not OpenImageIO directly: linking libOpenImageIO pulls in
// some 260 shared libraries (opencv, ffmpeg, gstreamer, dcmtk, openvdb...),
// and loading them took 0.41 s and 130 MB of memory at the start of every
// process, whether it touched an image or not: `hybridscape-cli --version`
// took 0.44 s, each import worker as long, and the test suite starts the
// CLI hundreds of times (783 before its first 15 suites had finished).
// OpenImageIO now lives in a module of its own (core/image_io_oiio.cpp,
// built as hybridscape-image-io.so), loaded on the first call here; a
// process that reads or writes no image never loads it.
//
// The module is found at $HS_IMAGE_IO_MODULE when set, else where the build
// put it, else beside the running program. Without it every call fails with
// a message naming where it looked (no image can be read or written; the
// rest of the program works).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace hs::image_io {

// Pixels are the file's values both ways: no alpha is multiplied into the
// colour on reading or divided out on writing (OpenImageIO's default for
// PNG does both; textures, the renderer and glTF mean straight colour).
// EXR's colour is premultiplied by that format's own definition, and is
// read and written as it is.

// Pixel types, in files and in memory.
enum class PixelType : uint8_t { UInt8, UInt16, Half, Float, Double, Other };

// What an image file holds, or is to hold.
struct Spec {
  int width = 0, height = 0, channels = 0;
  PixelType format = PixelType::UInt8;  // the file's pixel type
  std::vector<std::string> channelNames;  // empty: the format's own ("R", "G", "B", "A")
  // Metadata: text attributes ("ImageDescription", "compression",
  // "oiio:ColorSpace", "hs:spacing_x") and integer ones ("png:compressionLevel",
  // "CompressionQuality"). A file read fills `text` with its text attributes.
  std::vector<std::pair<std::string, std::string>> text;
  std::vector<std::pair<std::string, int>> ints;
  // The text attribute `name`, "" when there is none.
  std::string attribute(const std::string& name) const;
  // A spec with its size, channels and pixel type, no metadata.
  static Spec of(int width, int height, int channels, PixelType format);
};

// An image file open for reading.
class Reader {
 public:
  virtual ~Reader() = default;
  virtual const Spec& spec() const = 0;
  // The first `channels` channels of every pixel, converted to `as`
  // (integer files come back normalised to 0..1 as Half/Float/Double),
  // into `out`, which holds width * height * channels values. False with
  // `error` (the decoder's words) when the read fails, and also when it
  // returns but complained: libjpeg fills a JPEG cut short with grey and
  // only warns.
  virtual bool read(int channels, PixelType as, void* out, std::string& error) = 0;
};

// nullptr with `error` (OpenImageIO's reason, or the missing module) when
// the file cannot be opened as an image.
std::unique_ptr<Reader> open(const std::string& path, std::string& error);
// An image in memory, which must outlive the reader; `nameHint`
// ("embedded.png") only says which format to try first.
std::unique_ptr<Reader> openMemory(std::span<const uint8_t> bytes, const std::string& nameHint, std::string& error);

// Writes `pixels` (width * height * channels values of `memoryType`,
// converted to spec.format) to `path`, the format by its extension. False
// with `error` (without the path: callers name the file as they do).
bool writeFile(const std::string& path, const Spec& spec, PixelType memoryType, const void* pixels,
               std::string& error);
// The same, encoded in memory; `format` is OpenImageIO's format name
// ("png", "openexr", "jpeg", "tiff").
bool encode(const std::string& format, const Spec& spec, PixelType memoryType, const void* pixels,
            std::vector<uint8_t>& bytes, std::string& error);

// Whether the module is here (loading it if not yet loaded); `where` says
// where it was found or looked.
bool available(std::string* where = nullptr);

// Called on the loading thread just before the module is loaded (true) and
// just after (false), once per process. The import worker lifts its
// address-space limit around it: the module's ~260 libraries map 500-700
// MiB, which are not the file's doing. Set before the first image call.
using LoadHook = void (*)(bool before);
void setLoadHook(LoadHook hook);

// The module's side: one object with the calls above, returned by the
// module's `hs_image_io_backend` (extern "C"). Both sides are built together
// from this header, so C++ types cross between them.
struct Backend {
  virtual ~Backend() = default;
  virtual std::unique_ptr<Reader> open(const std::string& path, std::string& error) const = 0;
  virtual std::unique_ptr<Reader> openMemory(std::span<const uint8_t> bytes, const std::string& nameHint,
                                             std::string& error) const = 0;
  virtual bool writeFile(const std::string& path, const Spec& spec, PixelType memoryType, const void* pixels,
                         std::string& error) const = 0;
  virtual bool encode(const std::string& format, const Spec& spec, PixelType memoryType, const void* pixels,
                      std::vector<uint8_t>& bytes, std::string& error) const = 0;
};

}  // namespace hs::image_io
