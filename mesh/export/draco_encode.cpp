#include "mesh/export/draco_encode.h"

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hs::mesh::exporting {
namespace {

template <class T>
int addAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, const std::vector<T>& values,
                 const std::vector<uint32_t>& used) {
  constexpr int components = int(sizeof(T) / sizeof(float));
  draco::GeometryAttribute a;
  a.Init(type, nullptr, components, draco::DT_FLOAT32, false, sizeof(T), 0);
  const int id = mesh.AddAttribute(a, true, uint32_t(used.size()));
  draco::PointAttribute* pa = mesh.attribute(id);
  for (uint32_t i = 0; i < used.size(); ++i) pa->SetAttributeValue(draco::AttributeValueIndex(i), &values[used[i]]);
  return id;
}

}  // namespace

bool encodeDraco(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                 const std::vector<glm::vec2>& uvs, const uint32_t* indices, size_t indexCount, int positionBits,
                 DracoPrimitive& out, std::string& error) {
  out = DracoPrimitive{};
  if (positionBits < 8 || positionBits > 30) {
    error = "Draco position bits must be 8 to 30 (got " + std::to_string(positionBits) + ")";
    return false;
  }
  // The vertices this primitive uses, renumbered from 0.
  std::vector<uint32_t> used, local(positions.size(), std::numeric_limits<uint32_t>::max());
  for (size_t k = 0; k < indexCount; ++k)
    if (local[indices[k]] == std::numeric_limits<uint32_t>::max()) {
      local[indices[k]] = uint32_t(used.size());
      used.push_back(indices[k]);
    }
  draco::Mesh mesh;
  mesh.set_num_points(uint32_t(used.size()));
  out.positionId = addAttribute(mesh, draco::GeometryAttribute::POSITION, positions, used);
  if (!normals.empty()) out.normalId = addAttribute(mesh, draco::GeometryAttribute::NORMAL, normals, used);
  if (!uvs.empty()) out.uvId = addAttribute(mesh, draco::GeometryAttribute::TEX_COORD, uvs, used);
  for (size_t k = 0; k + 2 < indexCount; k += 3)
    mesh.AddFace({draco::PointIndex(local[indices[k]]), draco::PointIndex(local[indices[k + 1]]),
                  draco::PointIndex(local[indices[k + 2]])});

  // The position grid: from the bounds' low corner, across the largest
  // extent in 2^bits - 1 steps, as Draco's quantizer computes it (in float).
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (uint32_t v : used) lo = glm::min(lo, positions[v]), hi = glm::max(hi, positions[v]);
  const float range = std::max(std::max(hi.x - lo.x, hi.y - lo.y), std::max(hi.z - lo.z, 1e-6f));
  const int32_t maxQuantized = int32_t((uint32_t(1) << positionBits) - 1);
  const float inverseDelta = float(maxQuantized) / range, delta = range / float(maxQuantized);
  for (uint32_t v : used) {
    double moved2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      const int32_t q = int32_t(std::floor((positions[v][c] - lo[c]) * inverseDelta + 0.5f));
      const float back = float(q) * delta + lo[c];
      moved2 += (double(back) - double(positions[v][c])) * (double(back) - double(positions[v][c]));
    }
    out.maxPositionError = std::max(out.maxPositionError, std::sqrt(moved2));
  }
  out.lo = lo, out.hi = hi;

  draco::Encoder encoder;
  encoder.SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION, positionBits, 3, &lo.x, range);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, kDracoNormalBits);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, kDracoUvBits);
  encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
  encoder.SetTrackEncodedProperties(true);
  draco::EncoderBuffer buffer;
  const draco::Status s = encoder.EncodeMeshToBuffer(mesh, &buffer);
  if (!s.ok()) {
    error = std::string("Draco could not encode it (") + s.error_msg() + ")";
    return false;
  }
  out.bytes.assign(buffer.data(), buffer.size());
  out.points = uint32_t(encoder.num_encoded_points());
  out.faces = uint32_t(encoder.num_encoded_faces());
  return true;
}

}  // namespace hs::mesh::exporting
