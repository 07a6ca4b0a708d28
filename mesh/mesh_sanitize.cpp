#include "mesh/mesh_sanitize.h"

#include <cmath>

namespace hs::mesh {

void ensureSubmesh(MeshData& mesh) {
  if (mesh.submeshes.empty() && !mesh.indices.empty())
    mesh.submeshes.push_back({0, uint32_t(mesh.indices.size()), mesh.materials.empty() ? -1 : 0});
}

void sanitize(MeshData& mesh, ImportReport& report) {
  ensureSubmesh(mesh);
  const size_t nv = mesh.positions.size();
  std::vector<uint8_t> badVertex(nv, 0);
  size_t nonFinite = 0;
  for (size_t i = 0; i < nv; ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      badVertex[i] = 1;
      ++nonFinite;
    }
  }

  size_t outOfRange = 0, degenerate = 0, onBadVertex = 0;
  std::vector<uint32_t> kept;
  kept.reserve(mesh.indices.size());
  std::vector<Submesh> submeshes;
  for (const Submesh& s : mesh.submeshes) {
    Submesh out = s;
    out.firstIndex = uint32_t(kept.size());
    const size_t end = std::min<size_t>(size_t(s.firstIndex) + s.indexCount, mesh.indices.size());
    for (size_t i = s.firstIndex; i + 2 < end; i += 3) {
      const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
      if (a >= nv || b >= nv || c >= nv) {
        ++outOfRange;
        continue;
      }
      if (a == b || b == c || a == c) {
        ++degenerate;
        continue;
      }
      if (badVertex[a] || badVertex[b] || badVertex[c]) {
        ++onBadVertex;
        continue;
      }
      kept.insert(kept.end(), {a, b, c});
    }
    out.indexCount = uint32_t(kept.size()) - out.firstIndex;
    if (out.indexCount > 0) submeshes.push_back(out);
  }
  mesh.indices = std::move(kept);
  mesh.submeshes = std::move(submeshes);

  // Compact: drop vertices no face uses (the NaN ones among them), keeping
  // the file's vertex order.
  std::vector<uint32_t> remap(nv, UINT32_MAX);
  for (uint32_t idx : mesh.indices) remap[idx] = 0;
  uint32_t next = 0;
  for (size_t i = 0; i < nv; ++i)
    if (remap[i] != UINT32_MAX) remap[i] = next++;
  if (next != nv) {
    for (uint32_t& idx : mesh.indices) idx = remap[idx];
    auto compact = [&](auto& arr) {
      if (arr.size() != nv) return;
      std::remove_reference_t<decltype(arr)> out(next);
      for (size_t i = 0; i < nv; ++i)
        if (remap[i] != UINT32_MAX) out[remap[i]] = arr[i];
      arr = std::move(out);
    };
    compact(mesh.positions);
    compact(mesh.normals);
    compact(mesh.uvs);
  }

  report.nonFiniteVertices += nonFinite;
  report.outOfRangeFaces += outOfRange;
  report.degenerateFaces += degenerate;
  const std::string& f = report.file;
  if (nonFinite)
    report.warnings.push_back(f + ": " + std::to_string(nonFinite) +
                              " vertices have NaN or infinite coordinates; " +
                              std::to_string(onBadVertex) + " faces using them were dropped");
  if (outOfRange)
    report.warnings.push_back(f + ": " + std::to_string(outOfRange) +
                              " faces reference a vertex index past the end of the vertex list and were dropped");
  if (degenerate)
    report.warnings.push_back(f + ": " + std::to_string(degenerate) +
                              " faces repeat a vertex (zero area) and were dropped");
}

}  // namespace hs::mesh
