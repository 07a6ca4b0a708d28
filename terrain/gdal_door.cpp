#include "terrain/gdal_door.h"

#include "core/module_loader.h"

namespace hs::terrain::gdal_door {
namespace {

// Loaded once, on the first call, and kept for the rest of the process.
const LoadedModule& loaded() {
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
  static const LoadedModule m = loadModule(kSpec);
  return m;
}

}  // namespace

const Backend* backend(std::string& error) { return loaded().calls<Backend>(error); }

bool available(std::string* where) { return loaded().available(where); }

}  // namespace hs::terrain::gdal_door
