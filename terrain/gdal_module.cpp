// hybridscape-gdal.so's entry point (terrain/gdal_door.h, loaded by
// core/module_loader.h): the Backend whose calls are gdal_side's.
#include "terrain/gdal_side.h"

namespace hs::terrain {
namespace {

struct GdalBackend final : gdal_door::Backend {
  bool readDem(const std::string& path, const DemImportOptions& options, const Progress* progress,
               gdal_door::DemRaster& out, DemImportReport& report, std::string& error,
               bool& cancelled) const override {
    return gdal_side::readDem(path, options, progress, out, report, error, cancelled);
  }
  void fillInverseDistance(std::vector<float>& values, std::vector<uint8_t>& valid, int width, int height,
                           double maxDistancePixels, const Progress* progress) const override {
    gdal_side::fillInverseDistance(values, valid, width, height, maxDistancePixels, progress);
  }
  Status writeGeoTiff(const gdal_door::GeoTiffRaster& raster, const std::string& path) const override {
    return gdal_side::writeGeoTiff(raster, path);
  }
  bool transformPoints(const std::string& from, const std::string& to, std::vector<glm::dvec3>& points,
                       std::string& toDefinition, std::string& toName, std::string& error) const override {
    return gdal_side::transformPoints(from, to, points, toDefinition, toName, error);
  }
};

}  // namespace
}  // namespace hs::terrain

extern "C" __attribute__((visibility("default"))) const void* hs_gdal_backend() {
  static const hs::terrain::GdalBackend backend;
  return static_cast<const hs::terrain::gdal_door::Backend*>(&backend);
}
