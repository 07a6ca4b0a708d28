#include "meshproc/cluster_pages.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include "meshproc/cluster_parts.h"
#include "meshproc/position_key.h"

namespace hs::mesh {
namespace {

constexpr char kIndexMagic[4] = {'H', 'S', 'C', 'I'};
constexpr char kPageMagic[4] = {'H', 'S', 'C', 'P'};
constexpr uint32_t kVersion = 2;  // 2: groups, vertex counts, normals

struct Writer {
  std::vector<uint8_t> bytes;
  template <class T>
  void put(const T& v) {
    const size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &v, sizeof(T));
  }
  void sphere(const LodSphere& s) {
    put(s.centre.x), put(s.centre.y), put(s.centre.z), put(s.radius);
  }
};

// Reads what the writer wrote; a read past the end fails and stays failed.
struct Reader {
  const uint8_t* data;
  size_t size, at = 0;
  bool ok = true;
  template <class T>
  T get() {
    T v{};
    if (!ok || size - at < sizeof(T)) {
      ok = false;
      return v;
    }
    std::memcpy(&v, data + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  LodSphere sphere() {
    LodSphere s;
    s.centre.x = get<float>(), s.centre.y = get<float>(), s.centre.z = get<float>();
    s.radius = get<float>();
    return s;
  }
  bool magic(const char (&m)[4]) {
    for (char c : m)
      if (get<char>() != c) return false;
    return ok;
  }
};

bool finite(const LodSphere& s) {
  return std::isfinite(s.centre.x) && std::isfinite(s.centre.y) && std::isfinite(s.centre.z) &&
         std::isfinite(s.radius) && s.radius >= 0.0f;
}

// Up to float rounding (a relative 1e-5 of the radius, and half of
// merged()'s slack for the coordinates' own rounding far from the origin).
bool holds(const LodSphere& outer, const LodSphere& inner) {
  return glm::length(inner.centre - outer.centre) + inner.radius <=
         outer.radius * (1.0f + 1e-5f) + 1e-5f + 0.5f * coordinateSlack(outer);
}

size_t clusterBytes(size_t vertices, size_t triangles, bool uvs) {
  return 8 + vertices * (uvs ? 24 : 16) + triangles * 3;
}

// Octahedral unit vectors in two snorm16 (Cigolle et al. 2014): under
// 0.01 degrees off, 4 bytes instead of 12.
uint32_t packNormal(glm::vec3 n) {
  const float len = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(len > 0.0f)) return packNormal({0.0f, 0.0f, 1.0f});
  n /= len;
  glm::vec2 o(n.x, n.y);
  if (n.z < 0.0f)
    o = (1.0f - glm::abs(glm::vec2(o.y, o.x))) * glm::vec2(o.x >= 0.0f ? 1.0f : -1.0f, o.y >= 0.0f ? 1.0f : -1.0f);
  auto q = [](float v) { return uint32_t(uint16_t(int16_t(std::lround(std::clamp(v, -1.0f, 1.0f) * 32767.0f)))); };
  return q(o.x) | q(o.y) << 16;
}

glm::vec3 unpackNormal(uint32_t p) {
  glm::vec2 o(float(int16_t(p & 0xFFFF)) / 32767.0f, float(int16_t(p >> 16)) / 32767.0f);
  glm::vec3 n(o.x, o.y, 1.0f - std::abs(o.x) - std::abs(o.y));
  if (n.z < 0.0f) {
    const glm::vec2 f = (1.0f - glm::abs(glm::vec2(o.y, o.x))) *
                        glm::vec2(o.x >= 0.0f ? 1.0f : -1.0f, o.y >= 0.0f ? 1.0f : -1.0f);
    n.x = f.x, n.y = f.y;
  }
  return glm::normalize(n);
}

}  // namespace

std::unordered_map<uint64_t, glm::vec3> normalsByPosition(const ClusterHierarchy& h, const std::vector<uint32_t>& ids) {
  std::unordered_map<uint64_t, glm::vec3> sum;
  for (uint32_t id : ids) {
    const Cluster& cl = h.clusters[id];
    for (uint32_t t = 0; t < cl.triangleCount; ++t) {
      const uint32_t* i = &h.indices[cl.firstIndex + t * 3];
      const glm::vec3 n = glm::cross(h.positions[i[1]] - h.positions[i[0]], h.positions[i[2]] - h.positions[i[0]]);
      for (int k = 0; k < 3; ++k) sum[positionKey(h.positions[i[k]])] += n;
    }
  }
  return sum;
}

ClusterPageWriter::ClusterPageWriter(bool uvs, size_t pageBytes, std::function<void(std::vector<uint8_t>&&)> emit)
    : uvs_(uvs), pageBytes_(pageBytes), emit_(std::move(emit)) {}

void ClusterPageWriter::finish() {
  if (inPage_ == 0) return;
  // The count goes after the magic and version, written last.
  std::memcpy(page_.data() + 8, &inPage_, 4);
  emit_(std::move(page_));
  page_.clear();
  inPage_ = 0;
  ++pages_;
}

void ClusterPageWriter::add(uint32_t at, const ClusterHierarchy& h, uint32_t id,
                            const std::unordered_map<uint64_t, glm::vec3>& normals, ClusterIndexEntry& entry) {
  const Cluster& c = h.clusters[id];
  // The cluster's own vertices, in first use order.
  std::unordered_map<uint32_t, uint8_t> local;
  std::vector<uint32_t> verts;
  std::vector<uint8_t> tris;
  for (uint32_t i = 0; i < c.triangleCount * 3; ++i) {
    const uint32_t v = h.indices[c.firstIndex + i];
    auto [it, added] = local.try_emplace(v, uint8_t(verts.size()));
    if (added) verts.push_back(v);
    tris.push_back(it->second);
  }
  const size_t bytes = clusterBytes(verts.size(), c.triangleCount, uvs_);
  if (inPage_ > 0 && page_.size() + bytes > pageBytes_) finish();
  Writer w{std::move(page_)};
  if (inPage_ == 0) {
    for (char m : kPageMagic) w.put(m);
    w.put(kVersion);
    w.put(uint32_t(0));  // cluster count (finish)
  }
  w.put(at);
  w.put(uint16_t(verts.size()));
  w.put(uint16_t(c.triangleCount));
  for (uint32_t v : verts) w.put(h.positions[v].x), w.put(h.positions[v].y), w.put(h.positions[v].z);
  for (uint32_t v : verts) {
    const auto it = normals.find(positionKey(h.positions[v]));
    w.put(packNormal(it == normals.end() ? glm::vec3(0.0f) : it->second));
  }
  if (uvs_)
    for (uint32_t v : verts) w.put(h.uvs[v].x), w.put(h.uvs[v].y);
  w.bytes.insert(w.bytes.end(), tris.begin(), tris.end());
  page_ = std::move(w.bytes);
  ++inPage_;
  entry.page = pages_;
  entry.level = c.level;
  entry.triangleCount = c.triangleCount;
  entry.vertexCount = uint32_t(verts.size());
  entry.group = c.group;
  entry.parentGroup = c.parentGroup;
  entry.bounds = c.bounds;
  entry.lodBounds = c.lodBounds;
  entry.parentBounds = c.parentBounds;
  entry.error = c.error;
  entry.parentError = c.parentError;
}

namespace {

// Page p's first cluster, from the entries' pages (in order).
std::string fillPageFirst(ClusterIndex& index) {
  index.pageFirst.assign(size_t(index.pageCount) + 1, uint32_t(index.clusters.size()));
  uint32_t next = 0;
  for (uint32_t i = 0; i < index.clusters.size(); ++i) {
    const uint32_t p = index.clusters[i].page;
    if (p >= index.pageCount)
      return "cluster " + std::to_string(i) + ": its page " + std::to_string(p) + " is past the " +
             std::to_string(index.pageCount) + " pages";
    if (p + 1 < next) return "cluster " + std::to_string(i) + ": its page " + std::to_string(p) + " is out of order";
    while (next <= p) index.pageFirst[next++] = i;
  }
  return "";
}

}  // namespace

ClusterPages paginate(const ClusterHierarchy& h, size_t pageBytes) {
  ClusterPages out;
  out.index.origin = h.origin;
  out.index.hasUvs = !h.uvs.empty();
  ClusterPageWriter writer(out.index.hasUvs, pageBytes,
                           [&](std::vector<uint8_t>&& page) { out.pages.push_back(std::move(page)); });
  // Level by level, each group's children side by side (groups in the
  // order they were made, which follows the grouping's spatial order): a
  // cut refines a group only with all its children resident, so siblings
  // sharing a page keep the pages a view needs few.
  out.order.resize(h.clusters.size());
  std::iota(out.order.begin(), out.order.end(), 0u);
  std::stable_sort(out.order.begin(), out.order.end(), [&](uint32_t a, uint32_t b) {
    const Cluster &x = h.clusters[a], &y = h.clusters[b];
    return x.level != y.level ? x.level < y.level : x.parentGroup < y.parentGroup;
  });
  // Vertex normals: the faces around each position among the clusters of
  // its own level (by position, so both sides of a UV seam get one).
  std::unordered_map<uint64_t, glm::vec3> normals;
  for (uint32_t at = 0; at < out.order.size(); ++at) {
    const uint32_t id = out.order[at];
    if (at == 0 || h.clusters[out.order[at - 1]].level != h.clusters[id].level) {
      std::vector<uint32_t> level;
      for (uint32_t k = at; k < out.order.size() && h.clusters[out.order[k]].level == h.clusters[id].level; ++k)
        level.push_back(out.order[k]);
      normals = normalsByPosition(h, level);
    }
    ClusterIndexEntry e;
    writer.add(at, h, id, normals, e);
    out.index.clusters.push_back(e);
  }
  writer.finish();
  out.index.pageCount = writer.pages();
  out.index.groupCount = h.groups;
  fillPageFirst(out.index);
  return out;
}

PageExtent largestPage(const ClusterIndex& index) {
  PageExtent out;
  for (size_t p = 0; p + 1 < index.pageFirst.size(); ++p) {
    size_t v = 0, t = 0;
    for (uint32_t c = index.pageFirst[p]; c < index.pageFirst[p + 1]; ++c)
      v += index.clusters[c].vertexCount, t += index.clusters[c].triangleCount;
    out.vertices = std::max(out.vertices, v);
    out.indices = std::max(out.indices, t * 3);
  }
  return out;
}

std::vector<uint8_t> encodeClusterIndex(const ClusterIndex& index) {
  Writer w;
  for (char m : kIndexMagic) w.put(m);
  w.put(kVersion);
  w.put(index.origin.x), w.put(index.origin.y), w.put(index.origin.z);
  w.put(uint8_t(index.hasUvs ? 1 : 0));
  w.put(index.pageCount);
  w.put(index.groupCount);
  w.put(uint32_t(index.clusters.size()));
  for (const ClusterIndexEntry& e : index.clusters) {
    w.put(e.page), w.put(e.level), w.put(e.triangleCount), w.put(e.vertexCount), w.put(e.group), w.put(e.parentGroup);
    w.sphere(e.bounds), w.sphere(e.lodBounds), w.sphere(e.parentBounds);
    w.put(e.error), w.put(e.parentError);
  }
  return std::move(w.bytes);
}

std::string clusterIndexProblem(ClusterIndex& index) {
  if (!std::isfinite(index.origin.x) || !std::isfinite(index.origin.y) || !std::isfinite(index.origin.z))
    return "its origin is not finite";
  if (std::string p = fillPageFirst(index); !p.empty()) return p;
  // Each group's test, from the first cluster it made; every other cluster
  // it made, and every cluster simplified in it, must agree (the cut swaps
  // a group's children for what it made as one).
  std::vector<int64_t> madeBy(index.groupCount, -1);
  for (size_t i = 0; i < index.clusters.size(); ++i) {
    const ClusterIndexEntry& e = index.clusters[i];
    const std::string who = "cluster " + std::to_string(i) + " (level " + std::to_string(e.level) + ")";
    if (!finite(e.bounds) || !finite(e.lodBounds) || !finite(e.parentBounds))
      return who + ": a bounding sphere is not finite (or has a negative radius)";
    if (!std::isfinite(e.error) || e.error < 0.0f || std::isnan(e.parentError))
      return who + ": its error is not a finite number of metres";
    // Monotonic: what keeps a cut crack-free and its error honest.
    if (e.parentError < e.error)
      return who + ": its error " + std::to_string(e.error) + " m is larger than its parent's " +
             std::to_string(e.parentError) + " m (errors must grow up the hierarchy)";
    if (std::isfinite(e.parentError) && !holds(e.parentBounds, e.lodBounds))
      return who + ": its sphere is not inside its parent's";
    if (e.vertexCount < 3 || e.vertexCount > 256 || e.triangleCount == 0 || e.triangleCount > 512)
      return who + ": " + std::to_string(e.vertexCount) + " vertices and " + std::to_string(e.triangleCount) +
             " triangles (a cluster has 3-256 and 1-512)";
    const bool root = !std::isfinite(e.parentError);
    if ((e.group == kNoGroup) != (e.level == 0) || (e.parentGroup == kNoGroup) != root ||
        (e.group != kNoGroup && e.group >= index.groupCount) ||
        (e.parentGroup != kNoGroup && e.parentGroup >= index.groupCount))
      return who + ": its group ids do not fit its level and parent (" + std::to_string(index.groupCount) + " groups)";
    // A group is made after every group below it (cluster_cut.h walks down by id).
    if (e.group != kNoGroup && e.parentGroup != kNoGroup && e.parentGroup <= e.group)
      return who + ": its parent group " + std::to_string(e.parentGroup) + " comes before its own " +
             std::to_string(e.group);
    if (e.group != kNoGroup) {
      if (madeBy[e.group] < 0) madeBy[e.group] = int64_t(i);
      const ClusterIndexEntry& first = index.clusters[size_t(madeBy[e.group])];
      if (first.error != e.error || std::memcmp(&first.lodBounds, &e.lodBounds, sizeof e.lodBounds) != 0)
        return who + ": its group " + std::to_string(e.group) + " has another error or sphere in cluster " +
               std::to_string(madeBy[e.group]);
    }
  }
  for (size_t i = 0; i < index.clusters.size(); ++i) {
    const ClusterIndexEntry& e = index.clusters[i];
    if (e.parentGroup == kNoGroup) continue;
    const int64_t m = madeBy[e.parentGroup];
    if (m < 0 || index.clusters[size_t(m)].error != e.parentError)
      return "cluster " + std::to_string(i) + " (level " + std::to_string(e.level) + "): its parent group " +
             std::to_string(e.parentGroup) + (m < 0 ? " made no cluster" : " has another error");
  }
  return "";
}

std::optional<ClusterIndex> decodeClusterIndex(const uint8_t* data, size_t size, const std::string& what,
                                               std::string& error) {
  Reader r{data, size};
  if (!r.magic(kIndexMagic)) {
    error = what + ": not a cluster index";
    return std::nullopt;
  }
  if (const uint32_t v = r.get<uint32_t>(); r.ok && v != kVersion) {
    error = what + ": cluster index version " + std::to_string(v) + ", this build reads " + std::to_string(kVersion);
    return std::nullopt;
  }
  ClusterIndex index;
  index.origin.x = r.get<double>(), index.origin.y = r.get<double>(), index.origin.z = r.get<double>();
  index.hasUvs = r.get<uint8_t>() != 0;
  index.pageCount = r.get<uint32_t>();
  index.groupCount = r.get<uint32_t>();
  const uint32_t count = r.get<uint32_t>();
  constexpr size_t kEntryBytes = 6 * 4 + 3 * 16 + 2 * 4;
  if (r.ok && (size - r.at) / kEntryBytes < count) {
    error = what + ": truncated: it declares " + std::to_string(count) + " clusters, the bytes hold " +
            std::to_string((size - r.at) / kEntryBytes);
    return std::nullopt;
  }
  for (uint32_t i = 0; r.ok && i < count; ++i) {
    ClusterIndexEntry e;
    e.page = r.get<uint32_t>(), e.level = r.get<uint32_t>(), e.triangleCount = r.get<uint32_t>();
    e.vertexCount = r.get<uint32_t>(), e.group = r.get<uint32_t>(), e.parentGroup = r.get<uint32_t>();
    e.bounds = r.sphere(), e.lodBounds = r.sphere(), e.parentBounds = r.sphere();
    e.error = r.get<float>(), e.parentError = r.get<float>();
    index.clusters.push_back(e);
  }
  if (!r.ok) {
    error = what + ": truncated";
    return std::nullopt;
  }
  if (r.at != size) {
    error = what + ": " + std::to_string(size - r.at) + " bytes after its end (damaged)";
    return std::nullopt;
  }
  if (std::string p = clusterIndexProblem(index); !p.empty()) {
    error = what + ": " + p;
    return std::nullopt;
  }
  return index;
}

std::optional<std::vector<PageCluster>> decodeClusterPage(const uint8_t* data, size_t size, const ClusterIndex& index,
                                                          uint32_t page, const std::string& what, std::string& error) {
  const std::string where = what + ", page " + std::to_string(page);
  Reader r{data, size};
  if (!r.magic(kPageMagic)) {
    error = where + ": not a cluster page";
    return std::nullopt;
  }
  if (const uint32_t v = r.get<uint32_t>(); r.ok && v != kVersion) {
    error = where + ": page version " + std::to_string(v) + ", this build reads " + std::to_string(kVersion);
    return std::nullopt;
  }
  const uint32_t count = r.get<uint32_t>();
  std::vector<PageCluster> out;
  if (index.pageFirst.size() != size_t(index.pageCount) + 1 || page >= index.pageCount) {
    error = where + ": there is no such page in the index";
    return std::nullopt;
  }
  const uint32_t first = index.pageFirst[page];
  std::vector<bool> seen(index.pageFirst[page + 1] - first, false);
  for (uint32_t k = 0; r.ok && k < count; ++k) {
    PageCluster c;
    c.cluster = r.get<uint32_t>();
    const uint16_t vertices = r.get<uint16_t>(), triangles = r.get<uint16_t>();
    if (!r.ok) break;
    if (c.cluster >= index.clusters.size() || index.clusters[c.cluster].page != page) {
      error = where + ": holds cluster " + std::to_string(c.cluster) + ", which the index places elsewhere";
      return std::nullopt;
    }
    if (seen[c.cluster - first]) {
      error = where + ": holds cluster " + std::to_string(c.cluster) + " twice";
      return std::nullopt;
    }
    seen[c.cluster - first] = true;
    if (triangles != index.clusters[c.cluster].triangleCount) {
      error = where + ": cluster " + std::to_string(c.cluster) + " has " + std::to_string(triangles) +
              " triangles, the index says " + std::to_string(index.clusters[c.cluster].triangleCount);
      return std::nullopt;
    }
    if (vertices != index.clusters[c.cluster].vertexCount) {
      error = where + ": cluster " + std::to_string(c.cluster) + " has " + std::to_string(vertices) +
              " vertices, the index says " + std::to_string(index.clusters[c.cluster].vertexCount);
      return std::nullopt;
    }
    if (size - r.at < clusterBytes(vertices, triangles, index.hasUvs) - 8) {
      error = where + ": truncated in cluster " + std::to_string(c.cluster);
      return std::nullopt;
    }
    for (uint16_t v = 0; v < vertices; ++v) {
      glm::vec3 p;
      p.x = r.get<float>(), p.y = r.get<float>(), p.z = r.get<float>();
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        error = where + ": cluster " + std::to_string(c.cluster) + ", vertex " + std::to_string(v) +
                ": a position that is not finite";
        return std::nullopt;
      }
      c.positions.push_back(p);
    }
    for (uint16_t v = 0; v < vertices; ++v) c.normals.push_back(unpackNormal(r.get<uint32_t>()));
    if (index.hasUvs)
      for (uint16_t v = 0; v < vertices; ++v) {
        glm::vec2 uv;
        uv.x = r.get<float>(), uv.y = r.get<float>();
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) {
          error = where + ": cluster " + std::to_string(c.cluster) + ", vertex " + std::to_string(v) +
                  ": a UV that is not finite";
          return std::nullopt;
        }
        c.uvs.push_back(uv);
      }
    c.triangles.assign(data + r.at, data + r.at + size_t(triangles) * 3);
    r.at += size_t(triangles) * 3;
    for (uint8_t t : c.triangles)
      if (t >= vertices) {
        error = where + ": cluster " + std::to_string(c.cluster) + " has a triangle corner " + std::to_string(t) +
                " past its " + std::to_string(vertices) + " vertices";
        return std::nullopt;
      }
    out.push_back(std::move(c));
  }
  if (!r.ok) {
    error = where + ": truncated";
    return std::nullopt;
  }
  if (r.at != size) {
    error = where + ": " + std::to_string(size - r.at) + " bytes after its last cluster (damaged)";
    return std::nullopt;
  }
  // Every cluster the index puts here, once.
  const size_t expected = seen.size();
  if (out.size() != expected) {
    error = where + ": holds " + std::to_string(out.size()) + " clusters, the index puts " + std::to_string(expected) +
            " there";
    return std::nullopt;
  }
  return out;
}

}  // namespace hs::mesh
