#include "terrain/gdal_door.h"

#include "core/module_loader.h"

namespace hs::terrain::gdal_door {
namespace {

struct Loaded {
  const Backend* backend = nullptr;
  std::string where;
};

// Loaded once, on the first call, and kept for the rest of the process.
const Loaded& loaded() {
  static const Loaded l = [] {
    static constexpr ModuleSpec kSpec{
        .fileName = "hybridscape-gdal.so",
        .envVar = "HS_GDAL_MODULE",
#ifdef HS_GDAL_MODULE_PATH
        .buildPath = HS_GDAL_MODULE_PATH,
#else
        .buildPath = nullptr,
#endif
        .entrySymbol = "hs_gdal_backend",
        .kind = "GDAL module",
        .wraps = "GDAL and PROJ",
        .without = "no elevation model can be imported and no GeoTIFF written",
    };
    const LoadedModule m = loadModule(kSpec);
    return Loaded{static_cast<const Backend*>(m.entry), m.where};
  }();
  return l;
}

}  // namespace

const Backend* backend(std::string& error) {
  const Loaded& l = loaded();
  if (!l.backend) error = l.where;
  return l.backend;
}

bool available(std::string* where) {
  const Loaded& l = loaded();
  if (where) *where = l.where;
  return l.backend != nullptr;
}

}  // namespace hs::terrain::gdal_door
