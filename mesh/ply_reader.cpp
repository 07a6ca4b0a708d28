#include "mesh/ply_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "core/parallel.h"
#include "mesh/ply_body.h"
#include "mesh/ply_face_lists.h"
#include "mesh/ply_header.h"
#include "mesh/texture_decode.h"

namespace hs::mesh {
namespace {

using ply::Body;
using ply::Type;
using ply::decodeValue;

int slotOf(const std::string& name) {
  static const std::pair<const char*, int> kSlots[] = {
      {"x", 0},         {"y", 1},         {"z", 2},          {"nx", 3},        {"ny", 4},        {"nz", 5},
      {"u", 6},         {"s", 6},         {"texture_u", 6},  {"texture_s", 6}, {"v", 7},         {"t", 7},
      {"texture_v", 7}, {"texture_t", 7}, {"red", 8},        {"green", 8},     {"blue", 8},      {"diffuse_red", 8},
      {"diffuse_green", 8}, {"diffuse_blue", 8}};
  for (const auto& [n, s] : kSlots)
    if (name == n) return s;
  return -1;
}

struct Parsed {
  std::vector<glm::dvec3> positions;  // file axes
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;  // file convention (v up)
  bool hasNormals = false, hasUvs = false, hasColours = false;
  std::vector<uint32_t> corners;      // triangles, vertex indices
  std::vector<glm::vec2> cornerUvs;   // per corner, when faces carry texcoord lists
  std::vector<int> triangleTexture;   // per triangle, when faces carry texnumber
  bool faceUvs = false, faceTextures = false;
  size_t droppedOutOfRange = 0, droppedTooFew = 0, polygons = 0, stripTriangles = 0;
  // What the file declares (mesh/declared_counts.h): n - 2 per face list,
  // and the strips' triangles of non-zero area (a strip's joins repeat a
  // vertex by construction and are not primitives), dropped ones included.
  size_t declaredTriangles = 0;
  std::vector<std::string> firstProblems;
};

}  // namespace

bool readPly(const ByteSource& source, const std::string& baseDir, const ImportOptions& options,
             const Progress* progress, MeshData& out, ImportReport& report, std::string& error) {
  const std::string& file = source.name();
  ply::Header h;
  if (!ply::readHeader(source, h, error)) return false;
  const bool ascii = h.format == ply::Format::Ascii;
  const bool swap = h.format == ply::Format::BinaryBigEndian;  // this machine is little-endian
  Body body(source, h.bodyOffset, ascii, swap);
  Parsed p;
  uint64_t vertexCount = 0;
  for (const ply::Element& e : h.elements)
    if (e.name == "vertex") vertexCount = e.count;
  uint64_t total = 0, done = 0;
  for (const ply::Element& e : h.elements) total += e.count;

  std::vector<int64_t> list;
  std::vector<double> listValues;
  for (const ply::Element& e : h.elements) {
    const bool isVertex = e.name == "vertex", isFace = e.name == "face", isStrips = e.name == "tristrips";
    if (isVertex) {
      p.positions.reserve(size_t(e.count));
      for (const ply::Property& prop : e.properties) {
        const int s = slotOf(prop.name);
        p.hasNormals |= s >= 3 && s <= 5;
        p.hasUvs |= s == 6 || s == 7;
        p.hasColours |= s == 8;
      }
      if (p.hasNormals) p.normals.reserve(size_t(e.count));
      if (p.hasUvs) p.uvs.reserve(size_t(e.count));
    }
    // Elements we do not read, binary with fixed-size properties: skipped whole.
    const bool fixed = std::none_of(e.properties.begin(), e.properties.end(), [](const auto& q) { return q.list; });
    if (e.properties.empty()) {  // rows without data (the header check bounds their count)
      done += e.count;
      continue;
    }
    if (!isVertex && !isFace && !isStrips && !ascii && fixed) {
      if (!body.skip(e.count * e.minBytes(false))) {
        error = file + ": in element " + e.name + " (byte " + std::to_string(body.offset()) + "): " + body.error;
        return false;
      }
      done += e.count;
      continue;
    }
    // Binary vertices of fixed size: decoded a piece at a time on every
    // thread (each vertex from its own bytes, so the result does not
    // depend on the thread count).
    if (isVertex && !ascii && fixed && e.count > 0) {
      const size_t stride = size_t(e.minBytes(false));
      struct Field {
        int slot;
        size_t offset;
        Type type;
      };
      std::vector<Field> fields;
      size_t offset = 0;
      for (const ply::Property& prop : e.properties) {
        if (const int s = slotOf(prop.name); s >= 0 && s < 8) fields.push_back({s, offset, prop.type});
        offset += size_t(ply::typeSize(prop.type));
      }
      const size_t count = size_t(e.count);
      p.positions.assign(count, glm::dvec3(0.0));
      if (p.hasNormals) p.normals.assign(count, glm::vec3(0.0f));
      if (p.hasUvs) p.uvs.assign(count, glm::vec2(0.0f));
      const size_t perPiece = std::max<size_t>(1, Body::kPieceBytes / stride);
      for (size_t first = 0; first < count; first += perPiece) {
        const size_t n = std::min(perPiece, count - first);
        const uint64_t at = body.offset();
        const char* bytes = body.block(n * stride);
        if (!bytes) {
          error = file + ": in vertex " + std::to_string(first + 1) + " of " + std::to_string(count) + " (byte " +
                  std::to_string(at) + "): " + body.error;
          return false;
        }
        parallelFor(int64_t(n), 0, 16384, [&](int64_t lo, int64_t hi) {
          for (int64_t k = lo; k < hi; ++k) {
            const char* v = bytes + size_t(k) * stride;
            double slots[8] = {0, 0, 0, 0, 0, 0, 0, 0};
            for (const Field& f : fields) slots[f.slot] = decodeValue(f.type, v + f.offset, swap);
            const size_t i = first + size_t(k);
            p.positions[i] = glm::dvec3(slots[0], slots[1], slots[2]);
            if (p.hasNormals) p.normals[i] = glm::vec3(float(slots[3]), float(slots[4]), float(slots[5]));
            if (p.hasUvs) p.uvs[i] = glm::vec2(float(slots[6]), float(slots[7]));
          }
        });
        reportProgress(progress, 0.9 * double(done + first + n) / double(total), "Reading vertices");
        if (isCancelled(progress)) {
          error = file + ": import cancelled";
          return false;
        }
      }
      done += e.count;
      continue;
    }
    ply::FaceListLayout faceLayout;
    const bool faceLists = isFace && ply::faceListLayout(e, ascii, swap, faceLayout);
    ply::FaceListPiece piece;
    for (uint64_t i = 0; i < e.count; ++i) {
      // Binary face lists of 32-bit indices: a piece at a time on every
      // thread (mesh/ply_face_lists.h); what does not fit a piece is read
      // face by face below.
      if (faceLists) {
        size_t available = 0;
        const uint64_t pieceAt = body.offset();
        const char* bytes = body.window(Body::kPieceBytes, available);
        if (bytes) {
          const size_t before = p.corners.size();
          ply::readFaceLists(faceLayout, bytes, available, size_t(e.count - i), vertexCount, piece, p.corners);
          if (piece.faces > 0) {
            for (size_t f = 0; f < piece.faces && p.firstProblems.size() < 3; ++f) {
              if (piece.status[f] == ply::FaceStatus::Kept) continue;
              const std::string what = piece.status[f] == ply::FaceStatus::TooFew
                                           ? "a face with " + std::to_string(piece.corners[f]) + " corners (dropped)"
                                           : "a vertex index outside 0.." + std::to_string(vertexCount) +
                                                 " (the face is dropped)";
              p.firstProblems.push_back(file + ": " + e.name + " " + std::to_string(i + f + 1) + " of " +
                                        std::to_string(e.count) + " (byte " +
                                        std::to_string(pieceAt + piece.start[f]) + "): " + what);
            }
            for (size_t f = 0; f < piece.faces; ++f) {
              p.droppedTooFew += piece.status[f] == ply::FaceStatus::TooFew;
              p.droppedOutOfRange += piece.status[f] == ply::FaceStatus::OutOfRange;
            }
            p.declaredTriangles += piece.declaredTriangles;
            p.polygons += piece.polygons;
            p.triangleTexture.resize(p.triangleTexture.size() + (p.corners.size() - before) / 3, 0);
            body.advance(piece.bytes);
            i += piece.faces - 1;
            reportProgress(progress, 0.9 * double(done + i + 1) / double(total), "Reading " + e.name);
            if (isCancelled(progress)) {
              error = file + ": import cancelled";
              return false;
            }
            continue;
          }
        }
      }
      if ((i & 0xFFFF) == 0 && total > 0) {
        reportProgress(progress, 0.9 * double(done + i) / double(total), "Reading " + e.name);
        if (isCancelled(progress)) {
          error = file + ": import cancelled";
          return false;
        }
      }
      const uint64_t at = body.offset();
      auto fail = [&](const std::string& what) {
        error = file + ": in " + e.name + " " + std::to_string(i + 1) + " of " + std::to_string(e.count) + " (byte " +
                std::to_string(at) + "): " + what;
        return false;
      };
      double slots[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      int texnumber = 0;
      bool hasTexcoords = false;
      list.clear();
      listValues.clear();
      for (const ply::Property& prop : e.properties) {
        if (prop.list) {
          int64_t n = 0;
          if (!body.integer(prop.countType, n)) return fail(body.error);
          if (n < 0) return fail("a list of " + std::to_string(n) + " entries");
          // Each entry needs at least one byte (binary) or two (ASCII).
          if (uint64_t(n) > source.size() - std::min(source.size(), body.offset()))
            return fail("a list of " + std::to_string(n) + " entries runs past the end of the file");
          const bool indices = (isFace || isStrips) && (prop.name == "vertex_indices" || prop.name == "vertex_index");
          const bool texcoord = isFace && prop.name == "texcoord";
          if (indices && !ascii && (prop.type == Type::Int32 || prop.type == Type::UInt32)) {
            // The common case, read as one block: 32-bit indices.
            const char* q = body.block(size_t(n) * 4);
            if (!q) return fail(body.error);
            for (int64_t k = 0; k < n; ++k) {
              const double v = decodeValue(prop.type, q + 4 * k, swap);
              list.push_back(int64_t(v));
            }
            continue;
          }
          for (int64_t k = 0; k < n; ++k) {
            if (indices) {
              int64_t v = 0;
              if (!body.integer(prop.type, v)) return fail(body.error);
              list.push_back(v);
            } else {
              double v = 0.0;
              if (!body.value(prop.type, v)) return fail(body.error);
              if (texcoord) listValues.push_back(v);
            }
          }
          hasTexcoords |= texcoord;
        } else {
          double v = 0.0;
          if (!body.value(prop.type, v)) return fail(body.error);
          if (isVertex) {
            const int s = slotOf(prop.name);
            if (s >= 0 && s < 8) slots[s] = v;
          } else if (isFace && prop.name == "texnumber") {
            texnumber = int(v);
            p.faceTextures = true;
          }
        }
      }
      if (isVertex) {
        p.positions.emplace_back(slots[0], slots[1], slots[2]);
        if (p.hasNormals) p.normals.emplace_back(float(slots[3]), float(slots[4]), float(slots[5]));
        if (p.hasUvs) p.uvs.emplace_back(float(slots[6]), float(slots[7]));
        continue;
      }
      if (!isFace && !isStrips) continue;
      auto problem = [&](const std::string& what) {
        if (p.firstProblems.size() < 3)
          p.firstProblems.push_back(file + ": " + e.name + " " + std::to_string(i + 1) + " of " +
                                    std::to_string(e.count) + " (byte " + std::to_string(at) + "): " + what);
      };
      bool inRange = true;
      for (int64_t v : list)
        if (v >= int64_t(vertexCount) || (v < 0 && !(isStrips && v == -1))) inRange = false;
      if (isFace) {
        p.declaredTriangles += list.size() >= 3 ? list.size() - 2 : 0;
        if (list.size() < 3) {
          ++p.droppedTooFew;
          problem("a face with " + std::to_string(list.size()) + " corners (dropped)");
          continue;
        }
        if (!inRange) {
          ++p.droppedOutOfRange;
          problem("a vertex index outside 0.." + std::to_string(vertexCount) + " (the face is dropped)");
          continue;
        }
        const bool uv = hasTexcoords && listValues.size() == 2 * list.size();
        p.faceUvs |= uv;
        if (list.size() > 3) ++p.polygons;
        for (size_t k = 1; k + 1 < list.size(); ++k) {
          for (size_t c : {size_t(0), k, k + 1}) {
            p.corners.push_back(uint32_t(list[c]));
            if (p.faceUvs) {
              p.cornerUvs.resize(p.corners.size() - 1);  // earlier faces without UVs: zero
              p.cornerUvs.emplace_back(uv ? glm::vec2(float(listValues[2 * c]), float(listValues[2 * c + 1]))
                                          : glm::vec2(0.0f));
            }
          }
          p.triangleTexture.push_back(texnumber);
        }
      } else {  // a triangle strip, restarting at -1; every other triangle turns
        size_t start = 0;
        for (size_t k = 0; k <= list.size(); ++k) {
          if (k < list.size() && list[k] != -1) continue;
          for (size_t t = start; t + 2 < k; ++t)
            p.declaredTriangles += list[t] != list[t + 1] && list[t + 1] != list[t + 2] && list[t] != list[t + 2];
          start = k + 1;
        }
        if (!inRange) {
          ++p.droppedOutOfRange;
          problem("a vertex index outside 0.." + std::to_string(vertexCount) + " (the strip is dropped)");
          continue;
        }
        start = 0;
        for (size_t k = 0; k <= list.size(); ++k) {
          if (k < list.size() && list[k] != -1) continue;
          for (size_t t = start; t + 2 < k; ++t) {
            const bool odd = (t - start) % 2 == 1;
            const uint32_t a = uint32_t(list[odd ? t + 1 : t]), b = uint32_t(list[odd ? t : t + 1]),
                           c = uint32_t(list[t + 2]);
            if (a == b || b == c || a == c) continue;  // strip joins: no area by construction
            p.corners.insert(p.corners.end(), {a, b, c});
            p.triangleTexture.push_back(0);
            ++p.stripTriangles;
          }
          start = k + 1;
        }
      }
    }
    done += e.count;
  }
  if (p.faceUvs) p.cornerUvs.resize(p.corners.size());
  // Data after the declared elements: counts lowered by hand or by a tool
  // that went wrong. Read as declared, and said.
  if (body.offset() < source.size() && body.hasData())
    report.warnings.push_back(file + ": " + std::to_string(source.size() - body.offset()) +
                              " bytes of data follow the elements the header declares (from byte " +
                              std::to_string(body.offset()) + "); the rest is not read (the header's counts may be too low)");

  // Report what was declared against what is kept.
  report.verticesIn = size_t(vertexCount);
  report.trianglesIn = p.corners.size() / 3;
  report.declaredTriangles = p.declaredTriangles;
  report.declaredBy = "PLY face lists and tristrips (zero-area strip joins not counted)";
  report.outOfRangeFaces += p.droppedOutOfRange;
  report.degenerateFaces += p.droppedTooFew;
  report.polygonsTriangulated += p.polygons;
  for (const std::string& s : p.firstProblems) report.warnings.push_back(s);
  if (p.droppedOutOfRange + p.droppedTooFew > p.firstProblems.size())
    report.warnings.push_back(file + ": " + std::to_string(p.droppedOutOfRange + p.droppedTooFew) +
                              " faces or strips dropped in all (vertex indices out of range, or fewer than 3 corners)");
  if (p.hasColours)
    report.warnings.push_back(file + ": vertex colours are not imported (meshes have no colour channel yet)");
  if (p.positions.empty() || p.corners.empty()) {
    error = file + ": no triangles (" + std::to_string(vertexCount) + " vertices, " +
            std::to_string(p.corners.size() / 3) + " triangles)";
    return false;
  }

  // Axes and the provisional origin: doubles until the origin is subtracted.
  const bool zUp = options.up == UpAxis::Z;
  report.upAxisConverted = !zUp;
  auto axes = [zUp](glm::dvec3 v) { return zUp ? v : glm::dvec3(v.x, -v.z, v.y); };
  glm::dvec3 origin(0.0);
  for (const glm::dvec3& v : p.positions)
    if (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) {
      origin = glm::round(axes(v));
      break;
    }
  out = MeshData{};
  out.origin = origin;

  // Vertices: as in the file, or split per (vertex, corner UV) when faces
  // carry their own texture coordinates.
  if (p.faceUvs) {
    struct Key {
      uint32_t v;
      uint32_t u, w;
      bool operator==(const Key&) const = default;
    };
    struct Hash {
      size_t operator()(const Key& k) const { return (size_t(k.v) * 0x9E3779B97F4A7C15ull) ^ (size_t(k.u) << 1) ^ k.w; }
    };
    std::unordered_map<Key, uint32_t, Hash> index;
    index.reserve(p.corners.size());
    for (size_t c = 0; c < p.corners.size(); ++c) {
      Key k{p.corners[c], 0, 0};
      std::memcpy(&k.u, &p.cornerUvs[c].x, 4);
      std::memcpy(&k.w, &p.cornerUvs[c].y, 4);
      auto [it, added] = index.try_emplace(k, uint32_t(out.positions.size()));
      if (added) {
        out.positions.push_back(glm::vec3(axes(p.positions[k.v]) - origin));
        if (p.hasNormals) out.normals.push_back(glm::vec3(axes(glm::dvec3(p.normals[k.v]))));
        out.uvs.emplace_back(p.cornerUvs[c].x, 1.0f - p.cornerUvs[c].y);
      }
      out.indices.push_back(it->second);
    }
  } else {
    out.positions.reserve(p.positions.size());
    for (const glm::dvec3& v : p.positions) out.positions.push_back(glm::vec3(axes(v) - origin));
    if (p.hasNormals)
      for (const glm::vec3& n : p.normals) out.normals.push_back(glm::vec3(axes(glm::dvec3(n))));
    if (p.hasUvs)
      for (const glm::vec2& t : p.uvs) out.uvs.emplace_back(t.x, 1.0f - t.y);
    out.indices = std::move(p.corners);
  }

  // Textures named in the header; texnumber picks one per face.
  const size_t textures = h.textureFiles.size();
  for (size_t t = 0; t < textures; ++t) {
    Material m;
    m.name = std::filesystem::path(h.textureFiles[t]).stem().string();
    Texture tex;
    std::string texError, texNote;
    const std::string path = (std::filesystem::path(baseDir) / h.textureFiles[t]).string();
    if (!out.uvs.empty() && decodeTextureFile(path, tex, texError, &texNote)) {
      if (!texNote.empty()) report.warnings.push_back(file + ": " + texNote);
      tex.name = h.textureFiles[t];
      m.diffuseTexture = int(out.textures.size());
      out.textures.push_back(std::move(tex));
    } else if (!out.uvs.empty()) {
      if (options.strictTextures) {
        error = file + ": texture '" + h.textureFiles[t] + "': " + texError;
        return false;
      }
      report.warnings.push_back(file + ": texture '" + h.textureFiles[t] + "': " + texError +
                                " (drawn untextured)");
    }
    out.materials.push_back(std::move(m));
  }
  // One submesh per texture used, in texture order (triangles regrouped).
  if (textures > 1 && p.faceTextures) {
    std::vector<std::vector<uint32_t>> groups(textures);
    const size_t n = out.indices.size() / 3;
    for (size_t t = 0; t < n; ++t) {
      const int k = p.triangleTexture[t];
      const size_t g = k >= 0 && size_t(k) < textures ? size_t(k) : 0;
      groups[g].insert(groups[g].end(), out.indices.begin() + long(3 * t), out.indices.begin() + long(3 * t + 3));
    }
    out.indices.clear();
    for (size_t g = 0; g < textures; ++g) {
      if (groups[g].empty()) continue;
      out.submeshes.push_back({uint32_t(out.indices.size()), uint32_t(groups[g].size()), int(g)});
      out.indices.insert(out.indices.end(), groups[g].begin(), groups[g].end());
    }
  } else {
    out.submeshes.push_back({0, uint32_t(out.indices.size()), textures > 0 ? 0 : -1});
  }
  return true;
}

}  // namespace hs::mesh
