#pragma once
// Coordinate reference systems for DEM import/export: which local metric CRS
// to reproject to, how far a CRS's own "metres" are from ground metres, and
// geodesic distances on the WGS 84 ellipsoid (PROJ's geodesic routines).
#include <memory>
#include <string>

#include <ogr_srs_api.h>

namespace hs::terrain {

struct SrsDeleter {
  void operator()(void* s) const {
    if (s) OSRDestroySpatialReference(static_cast<OGRSpatialReferenceH>(s));
  }
};
using SrsPtr = std::unique_ptr<void, SrsDeleter>;

struct TransformDeleter {
  void operator()(void* t) const {
    if (t) OCTDestroyCoordinateTransformation(static_cast<OGRCoordinateTransformationH>(t));
  }
};
using TransformPtr = std::unique_ptr<void, TransformDeleter>;

// PROJ's transformation from `from` to `to` (null when there is none).
inline TransformPtr makeTransform(OGRSpatialReferenceH from, OGRSpatialReferenceH to) {
  return TransformPtr(OCTNewCoordinateTransformation(from, to));
}

// A spatial reference with x = easting/longitude, y = northing/latitude
// whatever the authority says (GIS axis order), from WKT, "EPSG:n", PROJ
// strings, ... (anything OSRSetFromUserInput takes). Null on failure.
SrsPtr makeSrs(const std::string& definition);
SrsPtr cloneSrs(OGRSpatialReferenceH srs);
std::string srsWkt(OGRSpatialReferenceH srs);
std::string srsName(OGRSpatialReferenceH srs);
int srsEpsg(OGRSpatialReferenceH srs);  // 0 if unknown

// EPSG code of the WGS 84 UTM zone containing (lon, lat): 326zz north, 327zz south.
int utmEpsgFor(double lonDegrees, double latDegrees);

// Ellipsoidal (WGS 84) distance in metres between two lon/lat points.
double geodesicDistance(double lon1, double lat1, double lon2, double lat2);

}  // namespace hs::terrain
