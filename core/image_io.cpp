#include "core/image_io.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>

namespace hs::image_io {
namespace {

constexpr const char* kModuleName = "hybridscape-image-io.so";

std::atomic<LoadHook> gLoadHook{nullptr};

struct Loaded {
  const Backend* backend = nullptr;
  std::string where;  // the module's path, or where it was looked for and why it failed
};

// Loaded once, on the first call, and kept (never unloaded: readers it made
// may outlive any caller's scope).
const Loaded& loaded() {
  static const Loaded l = [] {
    Loaded r;
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("HS_IMAGE_IO_MODULE"); env && *env) {
      candidates.push_back(env);
    } else {
#ifdef HS_IMAGE_IO_MODULE_PATH
      candidates.push_back(HS_IMAGE_IO_MODULE_PATH);
#endif
      std::error_code ec;
      const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
      if (!ec) candidates.push_back((self.parent_path() / kModuleName).string());
    }
    std::string tried;
    auto note = [&](const std::string& path, const std::string& why) {
      tried += (tried.empty() ? "" : ", ") + path + " (" + why + ")";
    };
    const LoadHook hook = gLoadHook.load();
    if (hook) hook(true);
    struct After {
      LoadHook hook;
      ~After() {
        if (hook) hook(false);
      }
    } after{hook};
    for (const std::string& path : candidates) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(path, ec)) {
        note(path, "not there");
        continue;
      }
      void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        const char* why = ::dlerror();
        note(path, why ? why : "cannot load");
        continue;
      }
      using Entry = const Backend* (*)();
      const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "hs_image_io_backend"));
      if (!entry) {
        note(path, "no hs_image_io_backend in it");
        ::dlclose(handle);
        continue;
      }
      r.backend = entry();
      r.where = path;
      return r;
    }
    r.where = "the image module " + std::string(kModuleName) + " (OpenImageIO) is missing, so no image can be read " +
              "or written; looked at " + (tried.empty() ? std::string("nothing") : tried) +
              "; HS_IMAGE_IO_MODULE names it";
    return r;
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
