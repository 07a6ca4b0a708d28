#include "meshproc/mesh_clean.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>

#include "core/parallel.h"
#include "mesh/nonmanifold_split.h"
#include "mesh/weld.h"

namespace hs::mesh {
namespace {

constexpr size_t kListed = 100;

void note(std::vector<uint32_t>& list, size_t index) {
  if (list.size() < kListed) list.push_back(uint32_t(index));
}

std::string firstOf(const std::vector<uint32_t>& list) {
  std::string s;
  for (size_t i = 0; i < list.size() && i < 5; ++i) s += (i ? ", " : "") + std::to_string(list[i]);
  return s + (list.size() > 5 ? ", ..." : "");
}

// Faces in submesh order with their submesh, whatever the input's ranges.
struct FaceList {
  std::vector<uint32_t> tri;    // 3 per face
  std::vector<uint32_t> group;  // submesh per face
  std::vector<uint32_t> input;  // input face index
};

}  // namespace

bool cleanMesh(MeshData& mesh, const CleanOptions& options, CleanReport& r, std::string& error,
               const Progress* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const unsigned threads = resolveThreads(options.threads);
  const size_t nv = mesh.vertexCount();
  const size_t nfIn = mesh.indices.size() / 3;
  r.verticesIn = nv;
  r.trianglesIn = nfIn;
  auto finish = [&](bool ok) {
    r.verticesOut = mesh.vertexCount();
    r.trianglesOut = mesh.triangleCount();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return ok;
  };
  if (nfIn == 0) {
    error = "the mesh has no faces (" + std::to_string(nv) + " vertices, 0 faces): nothing to clean or show";
    return finish(false);
  }
  reportProgress(progress, 0.0, "Cleaning");

  // 1. Quarantine.
  std::vector<uint8_t> badVertex(nv, 0);
  for (size_t v = 0; v < nv; ++v) {
    const glm::vec3& p = mesh.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      badVertex[v] = 1;
      ++r.nonFiniteVertices;
      note(r.nonFiniteVertexIndices, v);
    }
  }
  FaceList faces;
  faces.tri.reserve(nfIn * 3);
  auto addRange = [&](size_t begin, size_t end, uint32_t group) {
    for (size_t f = begin; f < end; ++f) {
      const uint32_t a = mesh.indices[f * 3], b = mesh.indices[f * 3 + 1], c = mesh.indices[f * 3 + 2];
      if (a >= nv || b >= nv || c >= nv) {
        ++r.outOfRangeFaces;
        note(r.outOfRangeFaceIndices, f);
        continue;
      }
      if (badVertex[a] || badVertex[b] || badVertex[c]) {
        ++r.facesOnNonFiniteVertices;
        continue;
      }
      faces.tri.insert(faces.tri.end(), {a, b, c});
      faces.group.push_back(group);
      faces.input.push_back(uint32_t(f));
    }
  };
  std::vector<Submesh> groups = mesh.submeshes;
  std::vector<uint8_t> covered(nfIn, 0);
  for (size_t g = 0; g < groups.size(); ++g) {
    const size_t b = std::min<size_t>(groups[g].firstIndex / 3, nfIn);
    const size_t e = std::min<size_t>((size_t(groups[g].firstIndex) + groups[g].indexCount) / 3, nfIn);
    size_t from = b;
    for (size_t f = b; f <= e; ++f)  // skip faces an earlier submesh already took
      if (f == e || covered[f]) {
        addRange(from, f, uint32_t(g));
        from = f + 1;
      } else {
        covered[f] = 1;
      }
  }
  if (std::find(covered.begin(), covered.end(), 0) != covered.end()) {
    const uint32_t g = uint32_t(groups.size());
    groups.push_back({0, 0, mesh.materials.empty() ? -1 : 0});
    size_t from = 0;
    for (size_t f = 0; f <= nfIn; ++f)
      if (f == nfIn || covered[f]) {
        addRange(from, f, g);
        from = f + 1;
      }
  }

  // 2. Weld exact duplicates (NaN vertices are unused by now; their
  //    positions weld among themselves and are dropped at the end).
  if (options.weldDuplicates) {
    uint32_t unique = 0;
    const std::vector<uint32_t> remap = weldMap(mesh.positions, mesh.uvs, mesh.normals, unique);
    r.duplicateVerticesWelded = nv - unique;
    if (unique != nv) {
      // Keep one representative per id (the first), the rest become unused.
      std::vector<uint32_t> first(unique, UINT32_MAX);
      for (size_t v = 0; v < nv; ++v)
        if (first[remap[v]] == UINT32_MAX) first[remap[v]] = uint32_t(v);
      for (uint32_t& i : faces.tri) i = first[remap[i]];
    }
  }
  reportProgress(progress, 0.3, "Cleaning: degenerate faces");

  // 3. Degenerate and duplicate faces.
  const size_t nf = faces.group.size();
  std::vector<uint8_t> keep(nf, 1);
  for (size_t f = 0; f < nf; ++f) {
    const uint32_t a = faces.tri[f * 3], b = faces.tri[f * 3 + 1], c = faces.tri[f * 3 + 2];
    if (a == b || b == c || a == c) {
      keep[f] = 0;
      ++r.repeatedIndexFaces;
      note(r.degenerateFaceIndices, faces.input[f]);
      continue;
    }
    const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
    const double area2 = glm::length(glm::cross(pb - pa, pc - pa));
    const double longest = std::max({glm::length(pb - pa), glm::length(pc - pb), glm::length(pa - pc)});
    // height = area2 / longest; zero-area when height <= tol * longest
    if (!(area2 > options.zeroAreaTolerance * longest * longest)) {
      keep[f] = 0;
      ++r.zeroAreaFaces;
      note(r.degenerateFaceIndices, faces.input[f]);
    }
  }
  if (options.removeDuplicateFaces) {
    // Same three vertices in the same turning order (the reverse order is a
    // legitimate back face). Rotate each face to start at its smallest id,
    // then find repeats with an open-addressing table.
    size_t cap = 16;
    while (cap < nf * 2) cap <<= 1;
    std::vector<uint32_t> table(cap, UINT32_MAX);
    auto canon = [&](size_t f, uint32_t (&k)[3]) {
      const uint32_t* t = &faces.tri[f * 3];
      const int m = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
      k[0] = t[m], k[1] = t[(m + 1) % 3], k[2] = t[(m + 2) % 3];
    };
    for (size_t f = 0; f < nf; ++f) {
      if (!keep[f]) continue;
      uint32_t k[3];
      canon(f, k);
      uint64_t h = (uint64_t(k[0]) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(k[1]) * 0xC2B2AE3D27D4EB4Full) ^
                   (uint64_t(k[2]) * 0x165667B19E3779F9ull);
      h ^= h >> 31;
      for (size_t slot = size_t(h) & (cap - 1);; slot = (slot + 1) & (cap - 1)) {
        if (table[slot] == UINT32_MAX) {
          table[slot] = uint32_t(f);
          break;
        }
        uint32_t o[3];
        canon(table[slot], o);
        if (o[0] == k[0] && o[1] == k[1] && o[2] == k[2]) {
          keep[f] = 0;
          ++r.duplicateFaces;
          note(r.degenerateFaceIndices, faces.input[f]);
          break;
        }
      }
    }
  }
  {
    size_t n = 0;
    for (size_t f = 0; f < nf; ++f)
      if (keep[f]) {
        for (size_t k = 0; k < 3; ++k) faces.tri[n * 3 + k] = faces.tri[f * 3 + k];
        faces.group[n] = faces.group[f];
        faces.input[n] = faces.input[f];
        ++n;
      }
    faces.tri.resize(n * 3);
    faces.group.resize(n);
    faces.input.resize(n);
  }
  if (faces.group.empty()) {
    error = "every face was removed: " +
            std::to_string(r.outOfRangeFaces + r.facesOnNonFiniteVertices) + " invalid (bad index or NaN vertex), " +
            std::to_string(r.repeatedIndexFaces + r.zeroAreaFaces) + " degenerate (zero area), " +
            std::to_string(r.duplicateFaces) + " duplicate; nothing usable is left";
    mesh.indices.clear();
    mesh.submeshes.clear();
    return finish(false);
  }
  if (isCancelled(progress)) {
    error = "cleaning cancelled";
    return finish(false);
  }
  reportProgress(progress, 0.6, "Cleaning: non-manifold edges and vertices");

  // 4. Non-manifold split, found at position level: a UV seam splits
  //    vertices in the index list, but the surface is still one piece
  //    there, and splitting it would tear the seam open. A fan that needs
  //    its own vertex gets a copy of each (position, UV, normal) vertex its
  //    corners use. Then 5. compaction into the output arrays.
  uint32_t count = uint32_t(nv);
  std::vector<uint32_t> copiedFrom;
  if (options.splitNonManifold) {
    uint32_t nPos = 0;
    const std::vector<uint32_t> posOf = weldMap(mesh.positions, {}, {}, nPos);
    std::vector<uint32_t> ptris(faces.tri.size());
    for (size_t c = 0; c < ptris.size(); ++c) ptris[c] = posOf[faces.tri[c]];
    // On a manifold mesh the split is one analysis and changes nothing.
    CornerTopology topo;
    std::vector<uint32_t> posCopies;
    const NonManifoldSplitStats s = splitNonManifold(ptris, nPos, posCopies, topo, threads);
    if (s.nonManifoldEdges > 0 || s.nonManifoldVertices > 0) {
      r.nonManifoldEdges = s.nonManifoldEdges;
      r.nonManifoldVertices = s.nonManifoldVertices;
      r.facesDetached = s.facesDetached;
      std::unordered_map<uint64_t, uint32_t> copyOf;  // (position copy, vertex) -> new vertex
      for (size_t c = 0; c < ptris.size(); ++c) {
        if (ptris[c] < nPos) continue;
        const uint64_t key = (uint64_t(ptris[c]) << 32) | faces.tri[c];
        auto [it, added] = copyOf.try_emplace(key, count);
        if (added) {
          copiedFrom.push_back(faces.tri[c]);
          ++count;
        }
        faces.tri[c] = it->second;
      }
      r.verticesAddedBySplit = copiedFrom.size();
    }
  }
  auto sourceOf = [&](uint32_t v) { return v < nv ? v : copiedFrom[v - nv]; };
  std::vector<uint32_t> outOf(count, UINT32_MAX);
  uint32_t next = 0;
  // Keep the input's vertex order, copies after the vertex they copy.
  for (uint32_t v : faces.tri) outOf[v] = 0;
  for (uint32_t v = 0; v < count; ++v)
    if (outOf[v] != UINT32_MAX) outOf[v] = next++;
  MeshData out;
  out.origin = mesh.origin;
  out.materials = std::move(mesh.materials);
  out.textures = std::move(mesh.textures);
  const bool hasUv = mesh.uvs.size() == nv, hasNormals = mesh.normals.size() == nv;
  out.positions.resize(next);
  if (hasUv) out.uvs.resize(next);
  if (hasNormals) out.normals.resize(next);
  for (uint32_t v = 0; v < count; ++v) {
    if (outOf[v] == UINT32_MAX) continue;
    const uint32_t s = sourceOf(v);
    out.positions[outOf[v]] = mesh.positions[s];
    if (hasUv) out.uvs[outOf[v]] = mesh.uvs[s];
    if (hasNormals) out.normals[outOf[v]] = mesh.normals[s];
  }
  {
    // Dropped vertices that are neither NaN nor welded duplicates.
    const long long dropped = (long long)(nv + copiedFrom.size()) - next;
    r.unusedVerticesRemoved = size_t(std::max<long long>(
        0, dropped - (long long)r.duplicateVerticesWelded - (long long)r.nonFiniteVertices));
  }
  // Faces grouped by submesh, in input order within each.
  std::vector<size_t> perGroup(groups.size(), 0);
  for (uint32_t g : faces.group) ++perGroup[g];
  std::vector<size_t> start(groups.size() + 1, 0);
  for (size_t g = 0; g < groups.size(); ++g) start[g + 1] = start[g] + perGroup[g];
  out.indices.resize(faces.tri.size());
  std::vector<size_t> cursor(start.begin(), start.end() - 1);
  for (size_t f = 0; f < faces.group.size(); ++f) {
    const size_t at = cursor[faces.group[f]]++;
    for (size_t k = 0; k < 3; ++k) out.indices[at * 3 + k] = outOf[faces.tri[f * 3 + k]];
  }
  for (size_t g = 0; g < groups.size(); ++g)
    if (perGroup[g]) out.submeshes.push_back({uint32_t(start[g] * 3), uint32_t(perGroup[g] * 3), groups[g].material});
  mesh = std::move(out);

  auto warn = [&](size_t n, const std::string& what) {
    if (n) r.warnings.push_back(std::to_string(n) + " " + what);
  };
  warn(r.nonFiniteVertices, "vertices have NaN or infinite coordinates (first: " + firstOf(r.nonFiniteVertexIndices) +
                                "); " + std::to_string(r.facesOnNonFiniteVertices) + " faces using them were quarantined");
  warn(r.outOfRangeFaces, "faces refer to a vertex past the end of the vertex list (first face: " +
                              firstOf(r.outOfRangeFaceIndices) + ") and were quarantined");
  warn(r.duplicateVerticesWelded, "exact duplicate vertices were welded");
  warn(r.repeatedIndexFaces, "faces repeat a vertex and were removed");
  warn(r.zeroAreaFaces, "faces have zero area and were removed");
  warn(r.duplicateFaces, "faces repeat another face exactly and were removed");
  warn(r.nonManifoldEdges, "non-manifold edges (3+ faces, or two faces running the same way) were split");
  warn(r.nonManifoldVertices, "bow-tie vertices (faces meeting only at a point) were split");
  warn(r.facesDetached, "faces on folded non-manifold edges were given their own vertices");
  return finish(true);
}

}  // namespace hs::mesh
