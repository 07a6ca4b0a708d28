#include "core/image_io.h"

#include <atomic>

#include "core/module_loader.h"

namespace hs::image_io {
namespace {

std::atomic<LoadHook> gLoadHook{nullptr};

// Loaded once, on the first call, and kept (never unloaded: readers it made
// may outlive any caller's scope).
const LoadedModule& loaded() {
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
  static const LoadedModule m = loadModule(kSpec, gLoadHook.load());
  return m;
}

// The module's calls, or null with `error` saying why there are none.
const Backend* backend(std::string& error) { return loaded().calls<Backend>(error); }

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

bool available(std::string* where) { return loaded().available(where); }

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
