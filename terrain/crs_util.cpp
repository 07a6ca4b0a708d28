#include "terrain/crs_util.h"

#include <algorithm>
#include <cmath>

#include <cpl_conv.h>
#include <geodesic.h>

namespace hs::terrain {

SrsPtr makeSrs(const std::string& definition) {
  OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
  if (OSRSetFromUserInput(s, definition.c_str()) != OGRERR_NONE) {
    OSRDestroySpatialReference(s);
    return nullptr;
  }
  OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
  return SrsPtr(s);
}

SrsPtr cloneSrs(OGRSpatialReferenceH srs) {
  if (!srs) return nullptr;
  OGRSpatialReferenceH s = OSRClone(srs);
  OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
  return SrsPtr(s);
}

std::string srsWkt(OGRSpatialReferenceH srs) {
  if (!srs) return {};
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
  if (OSRExportToWktEx(srs, &wkt, opts) != OGRERR_NONE || !wkt) {
    CPLFree(wkt);
    if (OSRExportToWkt(srs, &wkt) != OGRERR_NONE) return {};
  }
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

std::string srsName(OGRSpatialReferenceH srs) {
  if (!srs) return {};
  const char* n = OSRGetName(srs);
  return n ? n : "";
}

int srsEpsg(OGRSpatialReferenceH srs) {
  if (!srs) return 0;
  const char* auth = OSRGetAuthorityName(srs, nullptr);
  const char* code = OSRGetAuthorityCode(srs, nullptr);
  if (auth && code && std::string(auth) == "EPSG") return std::atoi(code);
  return 0;
}

int utmEpsgFor(double lon, double lat) {
  double l = std::fmod(lon + 180.0, 360.0);
  if (l < 0) l += 360.0;
  const int zone = std::clamp(int(l / 6.0) + 1, 1, 60);
  return (lat >= 0.0 ? 32600 : 32700) + zone;
}

double geodesicDistance(double lon1, double lat1, double lon2, double lat2) {
  geod_geodesic g;
  geod_init(&g, 6378137.0, 1.0 / 298.257223563);
  double s12 = 0.0;
  geod_inverse(&g, lat1, lon1, lat2, lon2, &s12, nullptr, nullptr);
  return s12;
}

}  // namespace hs::terrain
