#pragma once
// Georeferencing offsets. Photogrammetry tools write meshes in coordinates
// relative to an offset (single-precision tools cannot hold UTM metres) and
// put the offset in a file beside the mesh:
//   Pix4D         <project>_offset.xyz               "x y z"
//   OpenDroneMap  odm_georeferencing_model_geo.txt   line 1: the coordinate system
//                                                    ("WGS84 UTM 32N"), line 2: "easting northing"
//   plain         any text file whose first value line is "x y z" (or "x,y,z")
// World position = file position + offset, added in double to the mesh's
// origin, so two tiles land exactly where they belong relative to each other.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hs::mesh {

struct GeoOffset {
  glm::dvec3 offset{0.0};
  std::string kind;    // "pix4d", "odm", "xyz" or "manual"
  std::string source;  // the file read, or "set by hand"
  std::string crs;     // coordinate system named by the file (ODM), else empty
  std::string warning;  // for the import report: the offset may be cut short, else empty
};

// Reads an offset file of any of the kinds above (the kind is told by the
// name and content). False with `error` naming the file and line.
bool readGeoOffsetFile(const std::string& path, GeoOffset& out, std::string& error);

// Looks beside `meshPath` for an offset sidecar, in this order:
// <stem>_offset.xyz, the only *_offset.xyz in the folder,
// odm_georeferencing_model_geo.txt in the folder or ../odm_georeferencing/,
// <stem>.offset, <stem>_offset.txt, offset.xyz, offset.txt.
// Returns the first that reads; `tried` (optional) lists what was looked at
// and any file that failed to read with its error, for the import report.
std::optional<GeoOffset> findGeoOffsetSidecar(const std::string& meshPath,
                                              std::vector<std::string>* tried = nullptr);

// "auto", "none" or "x,y,z" / "x y z" (the CLI's --origin); false with
// `error` on anything else. `isAuto` tells the first case apart.
bool parseGeoOffset(const std::string& text, GeoOffset& out, bool& isAuto, bool& isNone, std::string& error);

}  // namespace hs::mesh
