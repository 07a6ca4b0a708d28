// ImportOptions' parameters, declared once (core/params.h).
#include "mesh/mesh_import.h"

namespace hs::mesh {

const std::vector<ParamDecl>& importOptionDecls() {
  static const std::vector<ParamDecl> decls = {
      {.key = "up", .option = "up", .label = "Up axis", .type = ParamType::Choice, .defaultValue = "auto",
       .choices = {"auto", "y", "z"},
       .help = "the file's up axis: auto (FBX says, glTF is Y, OBJ/PLY are taken as Y-up); scans in UTM are Z-up",
       .valueName = "A", .editor = true},
      {.key = "reader", .option = "reader", .label = "Reader", .type = ParamType::Choice, .defaultValue = "auto",
       .choices = {"auto", "obj", "assimp"}, .help = "force a reader (auto: the own OBJ reader for .obj)",
       .valueName = "R", .editor = true},
      {.key = "origin", .option = "origin", .label = "Origin", .type = ParamType::Text, .defaultValue = "none",
       .help = "georeferencing offset added to the file's coordinates: auto reads a sidecar beside each file (Pix4D "
               "*_offset.xyz, OpenDroneMap, offset.xyz), none takes them as they are, x,y,z sets it by hand, or "
               "an offset file",
       .valueName = "auto|none|x,y,z|FILE"},
      // An offset by hand: projected coordinates reach ±2e7 m (Web
      // Mercator), so the limit is wider than the world extent.
      {.key = "origin_offset_m", .label = "Origin offset", .unit = Unit::Metres, .min = -1e8, .max = 1e8,
       .help = "added to the file's coordinates", .valueName = "x,y,z", .count = 3, .editor = true},
      {.key = "strict_textures", .option = "strict-textures", .label = "Strict textures", .type = ParamType::Flag,
       .help = "fail if a texture cannot be loaded (default: warn)"},
      {.key = "strict", .option = "strict", .label = "Strict", .type = ParamType::Flag,
       .help = "fail if the triangles imported differ from those the file declares (a file cut short, faces "
               "dropped for bad indices, header counts that do not match the data; default: warn)"},
  };
  return decls;
}

}  // namespace hs::mesh
