// ProcessOptions' parameters, declared once (core/params.h).
//
// A maximum error of 0.1 mm to 1 km: below 0.1 mm no scan is measured, and
// the dialog's field shows four decimals.
#include "meshproc/mesh_process.h"

namespace hs::mesh {

const std::vector<ParamDecl>& processOptionDecls() {
  static const std::vector<ParamDecl> decls = [] {
    const ProcessOptions d;
    std::vector<ParamDecl> out = {
        {.key = "decimate_to", .option = "decimate-to", .label = "Decimate to", .type = ParamType::Text,
         .help = "decimate to a triangle count (500k, 2M, 120000) or a share of the triangles (10%)",
         .valueName = "N"},
    };
    appendParams(out, decimateTargetDecls());
    appendParams(out, {
        {.key = "max_error_m", .option = "max-error", .label = "Maximum error", .unit = Unit::Metres, .min = 1e-4,
         .max = 1000.0,
         .help = "decimate as far as a Hausdorff error of M metres allows (with --decimate-to: whichever comes "
                 "first)",
         .valueName = "M", .editor = true, .decimals = 4, .step = 0.001},
        {.key = "lods", .option = "lods", .label = "Levels of detail", .unit = Unit::Levels, .min = 0, .max = 8,
         .integer = true, .defaultValue = d.lodLevels,
         .help = "build N coarser levels of detail (a quarter each) with their measured error; the renderer picks "
                 "one per instance",
         .valueName = "N", .editor = true},
        {.key = "no_refine", .option = "no-refine", .label = "No vertex refinement", .type = ParamType::Flag,
         .help = "keep the decimator's least-squares vertex places: skip the refinement that moves the vertices "
                 "around the largest distances (7-36% less Hausdorff error, about half a measurement's time)"},
        {.key = "certify", .option = "certify", .label = "Certify the maximum error", .type = ParamType::Flag,
         .help = "also bound the Hausdorff error from above (no point is further), and judge --max-error by that "
                 "bound; up to 3x the measurement's time"},
        {.key = "clean", .option = "clean", .label = "Clean", .type = ParamType::Flag,
         .help = "clean without decimating (implied by the three above): weld duplicates, remove degenerate "
                 "faces, split non-manifold spots"},
    });
    return out;
  }();
  return decls;
}

}  // namespace hs::mesh
