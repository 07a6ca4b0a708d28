#include "mesh/obj_reader.h"

#include <charconv>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include "mesh/mtl_reader.h"
#include "mesh/texture_decode.h"

namespace hs::mesh {
namespace {

constexpr uint32_t kInvalid = UINT32_MAX;

struct Cursor {
  const char* p;
  const char* end;
  void skipSpace() {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
  }
  bool atEnd() {
    skipSpace();
    return p >= end;
  }
  std::string_view token() {
    skipSpace();
    const char* b = p;
    while (p < end && *p != ' ' && *p != '\t') ++p;
    return {b, size_t(p - b)};
  }
  bool number(double& v) {
    skipSpace();
    if (p < end && *p == '+') ++p;  // from_chars rejects a leading '+'
    const auto r = std::from_chars(p, end, v);
    if (r.ec != std::errc() || (r.ptr < end && *r.ptr != ' ' && *r.ptr != '\t')) return false;
    p = r.ptr;
    return true;
  }
};

// Corner of a face as written: 1-based or negative (relative) indices, 0 = absent.
struct Corner {
  int64_t v = 0, vt = 0, vn = 0;
};

bool parseCorner(std::string_view tok, Corner& c) {
  auto parseInt = [](std::string_view s, int64_t& out) {
    if (s.empty()) {
      out = 0;
      return true;
    }
    const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
    return r.ec == std::errc() && r.ptr == s.data() + s.size() && out != 0;
  };
  const size_t s1 = tok.find('/');
  if (s1 == std::string_view::npos) return parseInt(tok, c.v) && c.v != 0;
  if (!parseInt(tok.substr(0, s1), c.v) || c.v == 0) return false;
  const std::string_view rest = tok.substr(s1 + 1);
  const size_t s2 = rest.find('/');
  if (s2 == std::string_view::npos) return parseInt(rest, c.vt);
  return parseInt(rest.substr(0, s2), c.vt) && parseInt(rest.substr(s2 + 1), c.vn);
}

// Resolves a 1-based or negative OBJ index against the current count.
uint32_t resolve(int64_t idx, size_t count) {
  if (idx > 0) return idx <= int64_t(count) ? uint32_t(idx - 1) : kInvalid;
  if (idx < 0) return -idx <= int64_t(count) ? uint32_t(int64_t(count) + idx) : kInvalid;
  return kInvalid;
}

struct ComboKey {
  uint32_t v, vt, vn;
  bool operator==(const ComboKey&) const = default;
};
struct ComboHash {
  size_t operator()(const ComboKey& k) const {
    uint64_t h = (uint64_t(k.v) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(k.vt) * 0xC2B2AE3D27D4EB4Full) ^
                 (uint64_t(k.vn) * 0x165667B19E3779F9ull);
    return size_t(h ^ (h >> 32));
  }
};

}  // namespace

bool readObj(std::string_view text, const std::string& name, const std::string& baseDir,
             const ImportOptions& options, const Progress* progress, MeshData& out,
             ImportReport& report, std::string& error) {
  // A binary file (a renamed image, an FBX) is not an OBJ: say so instead of
  // reporting the first garbage line as malformed.
  const size_t probe = std::min<size_t>(text.size(), 4096);
  for (size_t i = 0; i < probe; ++i)
    if (text[i] == '\0') {
      error = name + ": not a text OBJ file (binary data at byte " + std::to_string(i) + ")";
      return false;
    }

  const bool zUp = options.up == UpAxis::Z;  // OBJ declares no axis: Y-up unless told
  report.upAxisConverted = !zUp;
  auto toZUp = [zUp](glm::dvec3 p) { return zUp ? p : glm::dvec3(p.x, -p.z, p.y); };

  std::vector<glm::vec3> positions;       // relative to `origin`
  std::vector<glm::vec2> texcoords;
  std::vector<glm::vec3> fileNormals;
  glm::dvec3 origin(0.0);
  bool haveOrigin = false;

  // Faces as resolved (position, texcoord, normal) index triples, fanned into triangles.
  std::vector<ComboKey> corners;
  std::vector<Submesh> submeshes;
  std::vector<MtlMaterial> mtl;
  std::unordered_map<std::string, int> materialIndex;  // name -> index in out.materials
  int currentMaterial = -1;
  bool anyTexcoordRef = false, anyNormalRef = false;
  size_t firstOutOfRangeLine = 0;

  auto lineError = [&](size_t lineNo, const char* lineBegin, const char* lineEnd,
                       const std::string& what) {
    const bool lastLine = lineEnd >= text.data() + text.size();
    const bool noNewline = text.empty() || text.back() != '\n';
    std::string shown(lineBegin, std::min<size_t>(size_t(lineEnd - lineBegin), 60));
    if (lastLine && noNewline)
      error = name + ":" + std::to_string(lineNo) +
              ": file is truncated: the last line stops in the middle of a statement ('" + shown +
              "')";
    else
      error = name + ":" + std::to_string(lineNo) + ": " + what + " ('" + shown + "')";
  };

  const char* p = text.data();
  const char* end = text.data() + text.size();
  size_t lineNo = 0;
  const size_t progressStep = 4u << 20;
  size_t nextProgress = progressStep;
  std::vector<Corner> faceCorners;

  while (p < end) {
    ++lineNo;
    const char* lineBegin = p;
    const char* nl = static_cast<const char*>(memchr(p, '\n', size_t(end - p)));
    const char* lineEnd = nl ? nl : end;
    p = nl ? nl + 1 : end;
    const char* contentEnd = lineEnd;
    if (contentEnd > lineBegin && contentEnd[-1] == '\r') --contentEnd;

    if (size_t(lineBegin - text.data()) >= nextProgress) {
      nextProgress += progressStep;
      reportProgress(progress, 0.9 * double(lineBegin - text.data()) / double(text.size()),
                     "Reading OBJ");
      if (isCancelled(progress)) {
        error = name + ": import cancelled";
        return false;
      }
    }

    Cursor c{lineBegin, contentEnd};
    c.skipSpace();
    if (c.p >= contentEnd || *c.p == '#') continue;
    const std::string_view key = c.token();

    if (key == "v") {
      glm::dvec3 v;
      if (!c.number(v.x) || !c.number(v.y) || !c.number(v.z)) {
        lineError(lineNo, lineBegin, contentEnd, "cannot read three vertex coordinates");
        return false;
      }
      v = toZUp(v);
      if (!haveOrigin && std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) {
        // Provisional origin: keeps floats small from the first vertex on,
        // so UTM coordinates never pass through single precision.
        origin = glm::round(v);
        haveOrigin = true;
      }
      positions.emplace_back(v - origin);
    } else if (key == "vt") {
      double u, w = 0.0;
      if (!c.number(u)) {
        lineError(lineNo, lineBegin, contentEnd, "cannot read texture coordinate");
        return false;
      }
      if (!c.atEnd() && !c.number(w)) {
        lineError(lineNo, lineBegin, contentEnd, "cannot read texture coordinate");
        return false;
      }
      // Stored with v = 0 at the image's top row (the order images are read in).
      texcoords.emplace_back(float(u), float(1.0 - w));
    } else if (key == "vn") {
      glm::dvec3 n;
      if (!c.number(n.x) || !c.number(n.y) || !c.number(n.z)) {
        lineError(lineNo, lineBegin, contentEnd, "cannot read three normal components");
        return false;
      }
      fileNormals.emplace_back(toZUp(n));
    } else if (key == "f") {
      faceCorners.clear();
      while (!c.atEnd()) {
        Corner corner;
        const std::string_view tok = c.token();
        if (!parseCorner(tok, corner)) {
          lineError(lineNo, lineBegin, contentEnd,
                    "cannot read face corner '" + std::string(tok) + "'");
          return false;
        }
        faceCorners.push_back(corner);
      }
      if (faceCorners.size() < 3) {
        lineError(lineNo, lineBegin, contentEnd, "a face needs at least 3 corners");
        return false;
      }
      if (faceCorners.size() > 3) ++report.polygonsTriangulated;
      if (submeshes.empty() || submeshes.back().material != currentMaterial)
        submeshes.push_back({uint32_t(corners.size()), 0, currentMaterial});
      bool outOfRange = false;
      ComboKey resolved[3];
      auto resolveCorner = [&](const Corner& k) {
        ComboKey r{resolve(k.v, positions.size()),
                   k.vt ? resolve(k.vt, texcoords.size()) : kInvalid - 1,
                   k.vn ? resolve(k.vn, fileNormals.size()) : kInvalid - 1};
        if (r.v == kInvalid || r.vt == kInvalid || r.vn == kInvalid) outOfRange = true;
        anyTexcoordRef |= k.vt != 0;
        anyNormalRef |= k.vn != 0;
        return r;
      };
      resolved[0] = resolveCorner(faceCorners[0]);
      for (size_t i = 1; i + 1 < faceCorners.size(); ++i) {
        resolved[1] = resolveCorner(faceCorners[i]);
        resolved[2] = resolveCorner(faceCorners[i + 1]);
        for (const auto& r : resolved) corners.push_back(outOfRange ? ComboKey{kInvalid, 0, 0} : r);
      }
      if (outOfRange && !firstOutOfRangeLine) firstOutOfRangeLine = lineNo;
    } else if (key == "usemtl") {
      c.skipSpace();
      const std::string mname(c.p, contentEnd);
      auto it = materialIndex.find(mname);
      if (it == materialIndex.end()) {
        Material m;
        m.name = mname;
        it = materialIndex.emplace(mname, int(out.materials.size())).first;
        out.materials.push_back(m);
      }
      currentMaterial = it->second;
    } else if (key == "mtllib") {
      c.skipSpace();
      const std::string lib(c.p, contentEnd);
      std::string mtlError;
      const auto path = (std::filesystem::path(baseDir) / lib).string();
      if (!readMtl(path, mtl, mtlError))
        report.warnings.push_back(name + ":" + std::to_string(lineNo) + ": " + mtlError);
    } else if (key == "l" || key == "p" || key == "curv" || key == "surf") {
      ++report.skippedLines;  // lines, points and free-form geometry are not meshes
    }
    // o, g, s, vp, and other statements carry nothing we draw.
  }
  if (!submeshes.empty())
    for (size_t i = 0; i < submeshes.size(); ++i)
      submeshes[i].indexCount =
          uint32_t((i + 1 < submeshes.size() ? submeshes[i + 1].firstIndex : corners.size()) -
                   submeshes[i].firstIndex);

  report.verticesIn = positions.size();
  report.trianglesIn = corners.size() / 3;
  if (firstOutOfRangeLine)
    report.warnings.push_back(name + ":" + std::to_string(firstOutOfRangeLine) +
                              ": face index out of range (first such face; the file has " +
                              std::to_string(positions.size()) + " vertices)");
  if (report.skippedLines)
    report.warnings.push_back(name + ": " + std::to_string(report.skippedLines) +
                              " line/point/curve statements were skipped (not triangles)");
  if (corners.empty()) {
    error = text.empty() ? name + ": file is empty (0 bytes)"
                         : name + ": no faces to import (" + std::to_string(positions.size()) +
                               " vertices, 0 faces)";
    return false;
  }

  // Build output vertices: one per distinct (position, texcoord, normal).
  // Scans without texcoords/normals map positions straight through.
  reportProgress(progress, 0.9, "Building vertices");
  out.origin = origin;
  out.indices.resize(corners.size());
  if (!anyTexcoordRef && !anyNormalRef) {
    out.positions = std::move(positions);
    for (size_t i = 0; i < corners.size(); ++i) out.indices[i] = corners[i].v;
  } else {
    std::unordered_map<ComboKey, uint32_t, ComboHash> combos;
    // Most positions have one (texcoord, normal) pair: remember the first
    // and only fall back to the hash map for seams.
    std::vector<uint32_t> first(positions.size(), kInvalid);
    std::vector<ComboKey> outKey;
    outKey.reserve(positions.size());
    for (size_t i = 0; i < corners.size(); ++i) {
      const ComboKey k = corners[i];
      if (k.v == kInvalid) {
        out.indices[i] = kInvalid;
        continue;
      }
      uint32_t idx = first[k.v];
      if (idx == kInvalid) {
        idx = first[k.v] = uint32_t(outKey.size());
        outKey.push_back(k);
      } else if (!(outKey[idx] == k)) {
        auto [it, inserted] = combos.try_emplace(k, uint32_t(outKey.size()));
        if (inserted) outKey.push_back(k);
        idx = it->second;
      }
      out.indices[i] = idx;
    }
    out.positions.resize(outKey.size());
    if (anyTexcoordRef) out.uvs.resize(outKey.size(), glm::vec2(0.0f));
    if (anyNormalRef) out.normals.resize(outKey.size(), glm::vec3(0.0f));
    bool partialNormals = false;
    for (size_t i = 0; i < outKey.size(); ++i) {
      const ComboKey& k = outKey[i];
      out.positions[i] = positions[k.v];
      if (anyTexcoordRef && k.vt < texcoords.size()) out.uvs[i] = texcoords[k.vt];
      if (anyNormalRef) {
        if (k.vn < fileNormals.size())
          out.normals[i] = fileNormals[k.vn];
        else
          partialNormals = true;
      }
    }
    // Normals on some faces only: regenerate them all rather than mix.
    if (partialNormals) out.normals.clear();
  }
  out.submeshes = std::move(submeshes);

  // Materials: resolve the names used by usemtl against the .mtl libraries.
  std::unordered_map<std::string, int> textureByPath;  // an atlas shared by materials loads once
  for (Material& m : out.materials) {
    const MtlMaterial* src = nullptr;
    for (const auto& cand : mtl)
      if (cand.name == m.name) src = &cand;
    if (!src) {
      if (!mtl.empty())
        report.warnings.push_back(name + ": material '" + m.name +
                                  "' is used but not defined in the material library");
      continue;
    }
    // Kd is a display colour (sRGB); the renderer shades in linear light.
    m.baseColor = glm::vec4(glm::pow(src->kd, glm::vec3(2.2f)), src->opacity);
    if (!src->diffuseMap.empty()) {
      const auto texPath = (std::filesystem::path(baseDir) / src->diffuseMap).string();
      if (auto it = textureByPath.find(texPath); it != textureByPath.end()) {
        m.diffuseTexture = it->second;
        continue;
      }
      Texture tex;
      std::string texError;
      reportProgress(progress, 0.92, "Loading textures");
      if (decodeTextureFile(texPath, tex, texError)) {
        m.diffuseTexture = textureByPath[texPath] = int(out.textures.size());
        tex.name = src->diffuseMap;
        out.textures.push_back(std::move(tex));
      } else {
        if (options.strictTextures) {
          error = name + ": material '" + m.name + "': " + texError;
          return false;
        }
        report.warnings.push_back(name + ": material '" + m.name + "': " + texError +
                                  " (the material is drawn untextured)");
      }
    }
  }
  return true;
}

}  // namespace hs::mesh
