// The image module (hybridscape-image-io.so): core/image_io.h's calls on
// OpenImageIO. The only code that includes OpenImageIO's headers outside
// tests; loaded by core/image_io.cpp on the first image call.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>

#include "core/image_io.h"

namespace hs::image_io {
namespace {

OIIO::TypeDesc toOiio(PixelType t) {
  switch (t) {
    case PixelType::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelType::UInt16: return OIIO::TypeDesc::UINT16;
    case PixelType::Half: return OIIO::TypeDesc::HALF;
    case PixelType::Float: return OIIO::TypeDesc::FLOAT;
    case PixelType::Double: return OIIO::TypeDesc::DOUBLE;
    case PixelType::Other: break;
  }
  return OIIO::TypeDesc::UNKNOWN;
}

PixelType fromOiio(OIIO::TypeDesc t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8: return PixelType::UInt8;
    case OIIO::TypeDesc::UINT16: return PixelType::UInt16;
    case OIIO::TypeDesc::HALF: return PixelType::Half;
    case OIIO::TypeDesc::FLOAT: return PixelType::Float;
    case OIIO::TypeDesc::DOUBLE: return PixelType::Double;
    default: return PixelType::Other;
  }
}

Spec fromOiio(const OIIO::ImageSpec& s) {
  Spec out;
  out.width = s.width, out.height = s.height, out.channels = s.nchannels;
  out.format = fromOiio(s.format);
  out.channelNames = s.channelnames;
  for (const OIIO::ParamValue& p : s.extra_attribs)
    if (p.type() == OIIO::TypeString) out.text.emplace_back(p.name().string(), p.get_string());
  return out;
}

// Pixels are written as given: without this OpenImageIO's PNG writer takes
// RGBA as premultiplied and divides the colour by the alpha (a texture
// texel (200, 100, 50, 128) was written as (255, 199, 99, 128)).
constexpr const char* kUnassociated = "oiio:UnassociatedAlpha";

OIIO::ImageSpec toOiio(const Spec& s) {
  OIIO::ImageSpec out(s.width, s.height, s.channels, toOiio(s.format));
  if (!s.channelNames.empty()) out.channelnames = s.channelNames;
  for (const auto& [name, value] : s.text) out.attribute(name, value);
  for (const auto& [name, value] : s.ints) out.attribute(name, value);
  if (!out.find_attribute(kUnassociated)) out.attribute(kUnassociated, 1);
  return out;
}

// Pixels are read as stored: without this OpenImageIO's PNG reader
// multiplies the colour by the alpha (the same texel came back as
// (100, 50, 25, 128), and fully transparent texels black), where glTF,
// FBX materials and the renderer mean straight colour.
const OIIO::ImageSpec& readConfig() {
  static const OIIO::ImageSpec config = [] {
    OIIO::ImageSpec c;
    c.attribute(kUnassociated, 1);
    return c;
  }();
  return config;
}

class OiioReader final : public Reader {
 public:
  OiioReader(std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy, std::unique_ptr<OIIO::ImageInput> in)
      : proxy_(std::move(proxy)), in_(std::move(in)), spec_(fromOiio(in_->spec())) {}
  ~OiioReader() override { in_->close(); }
  const Spec& spec() const override { return spec_; }
  bool read(int channels, PixelType as, void* out, std::string& error) override {
    const bool ok = in_->read_image(0, 0, 0, channels, toOiio(as), out);
    // A decoder may complain and still return true (see image_io.h).
    error = in_->geterror();
    return ok && error.empty();
  }

 private:
  std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy_;  // before in_: it reads from it until closed
  std::unique_ptr<OIIO::ImageInput> in_;
  Spec spec_;
};

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

class OiioBackend final : public Backend {
 public:
  std::unique_ptr<Reader> open(const std::string& path, std::string& error) const override {
    auto in = OIIO::ImageInput::open(path, &readConfig());
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(nullptr, std::move(in));
  }

  std::unique_ptr<Reader> openMemory(std::span<const uint8_t> bytes, const std::string& nameHint,
                                     std::string& error) const override {
    auto proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes.data(), bytes.size());
    // With a configuration OIIO 2.4 takes the proxy from it ("oiio:ioproxy"),
    // not from open()'s third argument, which it then ignores.
    OIIO::ImageSpec config = readConfig();
    void* p = proxy.get();
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &p);
    auto in = OIIO::ImageInput::open(nameHint, &config);
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(proxy), std::move(in));
  }

  bool writeFile(const std::string& path, const Spec& spec, PixelType memoryType, const void* pixels,
                 std::string& error) const override {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
      error = "cannot write this image format (" + OIIO::geterror() + ")";
      return false;
    }
    if (!out->open(path, toOiio(spec))) {
      error = "cannot create the file (" + out->geterror() + ")";
      return false;
    }
    if (!out->write_image(toOiio(memoryType), pixels) || !out->close()) {
      error = "write failed (" + out->geterror() + ")";
      return false;
    }
    return true;
  }

  bool encode(const std::string& format, const Spec& spec, PixelType memoryType, const void* pixels,
              std::vector<uint8_t>& bytes, std::string& error) const override {
    bytes.clear();
    MemoryFile proxy(bytes);
    auto out = OIIO::ImageOutput::create(format);
    if (!out) {
      error = "no writer for it (" + OIIO::geterror() + ")";
      return false;
    }
    if (!out->supports("ioproxy") || !out->set_ioproxy(&proxy)) {
      error = "its writer cannot encode to memory";
      return false;
    }
    const std::string nominal = "image." + format;
    if (!out->open(nominal, toOiio(spec)) || !out->write_image(toOiio(memoryType), pixels) || !out->close()) {
      error = out->geterror();
      return false;
    }
    return true;
  }
};

}  // namespace
}  // namespace hs::image_io

// The module's entry point (core/module_loader.h): its calls, as the
// Backend of image_io.h.
extern "C" __attribute__((visibility("default"))) const void* hs_image_io_backend() {
  static const hs::image_io::OiioBackend backend;
  return static_cast<const hs::image_io::Backend*>(&backend);
}
