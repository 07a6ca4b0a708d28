#include "render/mesh_lod.h"

#include <algorithm>
#include <cmath>

#include "meshproc/lod_chain.h"

namespace hs::render {

MeshLodChoice chooseMeshLod(const std::vector<double>& errors, const glm::dvec3& centreRel, double radius,
                            double worldScale, const RenderView& view, double thresholdPixels) {
  MeshLodChoice c;
  const double scale = std::isfinite(worldScale) && worldScale > 0 ? worldScale : 1.0;
  c.distance = std::max(0.0, glm::length(centreRel) - radius * scale);
  if (errors.size() < 2 || !(c.distance > 0) || !(thresholdPixels > 0)) return c;
  // An error e seen at distance d on an instance scaled by s covers as many
  // pixels as e at d / s unscaled: one division instead of scaling every level.
  const double d = c.distance / scale;
  c.level = mesh::selectLod(errors, d, view.fovY, double(view.height), thresholdPixels);
  c.projectedErrorPixels = mesh::projectedErrorPixels(errors[size_t(c.level)], d, view.fovY, double(view.height));
  return c;
}

}  // namespace hs::render
