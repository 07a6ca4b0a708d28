#include "core/module_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace hs {

LoadedModule loadModule(const ModuleSpec& spec, ModuleLoadHook hook) {
  LoadedModule r;
  std::vector<std::string> candidates;
  if (const char* env = std::getenv(spec.envVar); env && *env) {
    candidates.push_back(env);
  } else {
    if (spec.buildPath && *spec.buildPath) candidates.push_back(spec.buildPath);
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((self.parent_path() / spec.fileName).string());
  }
  std::string tried;
  auto note = [&](const std::string& path, const std::string& why) {
    tried += (tried.empty() ? "" : ", ") + path + " (" + why + ")";
  };
  if (hook) hook(true);
  struct After {
    ModuleLoadHook hook;
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
    using Entry = const void* (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(handle, spec.entrySymbol));
    if (!entry) {
      note(path, std::string("no ") + spec.entrySymbol + " in it");
      ::dlclose(handle);
      continue;
    }
    r.entry = entry();
    r.where = path;
    return r;
  }
  r.where = std::string("the ") + spec.kind + " " + spec.fileName + " (" + spec.wraps + ") is missing, so " +
            spec.without + "; looked at " + (tried.empty() ? std::string("nothing") : tried) + "; " + spec.envVar +
            " names it";
  return r;
}

}  // namespace hs
