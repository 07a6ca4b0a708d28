#include "core/image_io.h"

#include <atomic>

#include "core/module_loader.h"

namespace hs::image_io {
namespace {

std::atomic<LoadHook> gLoadHook{nullptr};

struct Loaded {
  const Backend* backend = nullptr;
  std::string where;  // the module's path, or where it was looked for and why it failed
};

// Loaded once, on the first call, and kept (never unloaded: readers it made
// may outlive any caller's scope).
const Loaded& loaded() {
  static const Loaded l = [] {
    static constexpr ModuleSpec kSpec{
        .fileName = "hybridscape-image-io.so",
        .envVar = "HS_IMAGE_IO_MODULE",
#ifdef HS_IMAGE_IO_MODULE_PATH
        .buildPath = HS_IMAGE_IO_MODULE_PATH,
#else
        .buildPath = nullptr,
#endif
        .entrySymbol = "hs_image_io_backend",
        .kind = "image module",
        .wraps = "OpenImageIO",
        .without = "no image can be read or written",
    };
    const LoadedModule m = loadModule(kSpec, gLoadHook.load());
    return Loaded{static_cast<const Backend*>(m.entry), m.where};
  }();
  return l;
}

// The module's calls, or null with `error` saying why there are none.
const Backend* backend(std::string& error) {
  const Loaded& l = loaded();
  if (!l.backend) error = l.where;
  return l.backend;
}

}  // namespace

Spec Spec::of(int width, int height, int channels, PixelType format) {
  Spec s;
  s.width = width, s.height = height, s.channels = channels, s.format = format;
  return s;
}

std::string Spec::attribute(const std::string& name) const {
  for (const auto& [n, v] : text)
    if (n == name) return v;
  return {};
}

void setLoadHook(LoadHook hook) { gLoadHook.store(hook); }

bool available(std::string* where) {
  const Loaded& l = loaded();
  if (where) *where = l.where;
  return l.backend != nullptr;
}

std::unique_ptr<Reader> open(const std::string& path, std::string& error) {
  const Backend* b = backend(error);
  return b ? b->open(path, error) : nullptr;
}

std::unique_ptr<Reader> openMemory(std::span<const uint8_t> bytes, const std::string& nameHint, std::string& error) {
  const Backend* b = backend(error);
  return b ? b->openMemory(bytes, nameHint, error) : nullptr;
}

bool writeFile(const std::string& path, const Spec& spec, PixelType memoryType, const void* pixels,
               std::string& error) {
  const Backend* b = backend(error);
  return b && b->writeFile(path, spec, memoryType, pixels, error);
}

bool encode(const std::string& format, const Spec& spec, PixelType memoryType, const void* pixels,
            std::vector<uint8_t>& bytes, std::string& error) {
  const Backend* b = backend(error);
  return b && b->encode(format, spec, memoryType, pixels, bytes, error);
}

}  // namespace hs::image_io
