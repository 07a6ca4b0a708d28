#include "mesh/obj_reader.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "core/parallel.h"
#include "mesh/mtl_reader.h"
#include "mesh/texture_decode.h"

// How the reader scales (photogrammetry OBJs run to gigabytes):
//   1. the text is cut into chunks at line starts;
//   2. pass A, in parallel: each chunk counts its lines and its v, vt, vn and
//      triangle corners (a cheap scan, no number parsing);
//   3. prefix sums give every chunk the line number, vertex numbers and
//      corner offset it starts at, and the output arrays are allocated once
//      at their final size;
//   4. pass B, in parallel: each chunk parses its lines straight into those
//      arrays at its offsets, resolving face indices (absolute and relative)
//      against the global counts it now knows;
//   5. serially: materials, submeshes, messages in file order, then the
//      vertex build, which writes the final indices over the corner array.
// No per-chunk copies are merged, so memory stays near the final mesh; when
// the text is a file mapping, each chunk's pages are dropped from memory as
// soon as a pass is done with them. Results, messages and line numbers are
// the same for any number of threads, and the same as a single pass.

namespace hs::mesh {
namespace {

constexpr uint32_t kInvalid = UINT32_MAX;
constexpr uint32_t kAbsent = kInvalid - 1;  // corner written without vt / vn

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

enum class Key { None, V, Vt, Vn, F, Usemtl, Mtllib, Skipped, Other };

Key classify(std::string_view key) {
  if (key == "v") return Key::V;
  if (key == "vt") return Key::Vt;
  if (key == "vn") return Key::Vn;
  if (key == "f") return Key::F;
  if (key == "usemtl") return Key::Usemtl;
  if (key == "mtllib") return Key::Mtllib;
  if (key == "l" || key == "p" || key == "curv" || key == "surf") return Key::Skipped;
  return Key::Other;  // o, g, s, vp and others carry nothing we draw
}

// Calls fn(lineBegin, contentEnd, lineEnd) for every line of [begin, end);
// contentEnd excludes a trailing '\r'. Stops early when fn returns false.
template <class Fn>
void forEachLine(const char* begin, const char* end, Fn&& fn) {
  for (const char* p = begin; p < end;) {
    const char* nl = static_cast<const char*>(memchr(p, '\n', size_t(end - p)));
    const char* lineEnd = nl ? nl : end;
    const char* contentEnd = lineEnd;
    if (contentEnd > p && contentEnd[-1] == '\r') --contentEnd;
    if (!fn(p, contentEnd, lineEnd)) return;
    p = nl ? nl + 1 : end;
  }
}

struct Chunk {
  const char* begin = nullptr;
  const char* end = nullptr;
  // Pass A: what the chunk holds.
  size_t newlines = 0, v = 0, vt = 0, vn = 0, corners = 0;
  bool vtRefs = false, vnRefs = false;
  // Where it starts in the file (prefix sums of the above).
  size_t line0 = 0, v0 = 0, vt0 = 0, vn0 = 0, corner0 = 0;
  // Pass B: what happened, merged in file order afterwards.
  std::string error;  // first fatal problem (messages name the line)
  size_t firstOutOfRangeLine = 0;
  size_t polygons = 0, skipped = 0;
  bool anyTexcoordRef = false, anyNormalRef = false;
  struct Usemtl {
    size_t corner;  // faces from this corner on use the material
    std::string name;
  };
  struct Mtllib {
    size_t line;
    std::string name;
  };
  std::vector<Usemtl> usemtl;
  std::vector<Mtllib> mtllib;
};

// Drops the whole pages of [b, e) from this process's memory: the file
// stays in the page cache, but its pages stop counting towards our peak
// memory once a pass is done with them. Only valid on a file mapping.
void releasePages(const char* b, const char* e) {
  static const size_t page = size_t(sysconf(_SC_PAGESIZE));
  const uintptr_t lo = (reinterpret_cast<uintptr_t>(b) + page - 1) & ~(page - 1);
  const uintptr_t hi = reinterpret_cast<uintptr_t>(e) & ~(page - 1);
  if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_DONTNEED);
}

}  // namespace

bool readObj(std::string_view text, const std::string& name, const std::string& baseDir,
             const ImportOptions& options, const Progress* progress, MeshData& out,
             ImportReport& report, std::string& error, bool releaseInput) {
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
  const char* const textBegin = text.data();
  const char* const textEnd = text.data() + text.size();

  auto lineError = [&](size_t lineNo, const char* lineBegin, const char* lineEnd, const std::string& what) {
    const bool lastLine = lineEnd >= textEnd;
    const bool noNewline = text.empty() || text.back() != '\n';
    std::string shown(lineBegin, std::min<size_t>(size_t(lineEnd - lineBegin), 60));
    if (lastLine && noNewline)
      return name + ":" + std::to_string(lineNo) +
             ": file is truncated: the last line stops in the middle of a statement ('" + shown + "')";
    return name + ":" + std::to_string(lineNo) + ": " + what + " ('" + shown + "')";
  };

  // Provisional origin: the first finite vertex, rounded, keeps floats small
  // from the first vertex on, so UTM coordinates never pass through single
  // precision. Found before the parallel passes, which all need it.
  glm::dvec3 origin(0.0);
  size_t originVertex = SIZE_MAX;  // vertices before it are NaN/Inf, stored as read
  size_t scanned = 0;
  forEachLine(textBegin, textEnd, [&](const char* b, const char* ce, const char*) {
    Cursor c{b, ce};
    c.skipSpace();
    if (c.p >= ce || *c.p == '#' || c.token() != "v") return true;
    glm::dvec3 v;
    if (!c.number(v.x) || !c.number(v.y) || !c.number(v.z)) return false;  // pass B reports it
    v = toZUp(v);
    if (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) {
      origin = glm::round(v);
      originVertex = scanned;
      return false;
    }
    ++scanned;
    return true;
  });

  // Chunks: about eight per worker so uneven chunks balance, never smaller
  // than 4 MB (a small file is one chunk, read exactly like a single pass).
  const unsigned threads = resolveThreads(0);
  const size_t target = std::max<size_t>(size_t(4) << 20, text.size() / (size_t(threads) * 8) + 1);
  std::vector<Chunk> chunks;
  for (const char* p = textBegin; p < textEnd || chunks.empty();) {
    Chunk ch;
    ch.begin = p;
    const char* cut = p + std::min<size_t>(target, size_t(textEnd - p));
    if (cut < textEnd) {
      const char* nl = static_cast<const char*>(memchr(cut, '\n', size_t(textEnd - cut)));
      cut = nl ? nl + 1 : textEnd;
    }
    ch.end = cut;
    chunks.push_back(ch);
    p = cut;
    if (p >= textEnd) break;
  }

  // Pass A: counts.
  std::atomic<bool> stop{false};
  parallelTasks(chunks.size(), threads, [&](size_t k, unsigned) {
    if (stop) return;
    Chunk& ch = chunks[k];
    forEachLine(ch.begin, ch.end, [&](const char* b, const char* ce, const char* le) {
      ch.newlines += le < ch.end;
      Cursor c{b, ce};
      c.skipSpace();
      if (c.p >= ce || *c.p == '#') return true;
      switch (classify(c.token())) {
        case Key::V: ++ch.v; break;
        case Key::Vt: ++ch.vt; break;
        case Key::Vn: ++ch.vn; break;
        case Key::F: {
          size_t n = 0;
          while (!c.atEnd()) {
            const std::string_view tok = c.token();
            ++n;
            const size_t s1 = tok.find('/');
            if (s1 == std::string_view::npos) continue;
            const size_t s2 = tok.find('/', s1 + 1);
            ch.vtRefs |= (s2 == std::string_view::npos ? tok.size() : s2) > s1 + 1;
            ch.vnRefs |= s2 != std::string_view::npos && s2 + 1 < tok.size();
          }
          if (n >= 3) ch.corners += (n - 2) * 3;
          break;
        }
        default: break;
      }
      return true;
    });
    if (releaseInput) releasePages(ch.begin, ch.end);
    if (isCancelled(progress)) stop = true;
  });
  // One report once the file is scanned, whatever the timing of the
  // workers below (only the calling thread reports, and it may finish its
  // chunks before the others cross a reporting step).
  if (!stop) reportProgress(progress, 0.05, "Reading OBJ");
  if (stop || isCancelled(progress)) {
    error = name + ": import cancelled";
    return false;
  }

  // Where each chunk starts, and the arrays at their final size.
  size_t nv = 0, nvt = 0, nvn = 0, nc = 0, lines = 0;
  bool vtRefs = false, vnRefs = false;
  for (Chunk& ch : chunks) {
    ch.line0 = lines, ch.v0 = nv, ch.vt0 = nvt, ch.vn0 = nvn, ch.corner0 = nc;
    lines += ch.newlines, nv += ch.v, nvt += ch.vt, nvn += ch.vn, nc += ch.corners;
    vtRefs |= ch.vtRefs, vnRefs |= ch.vnRefs;
  }
  std::vector<glm::vec3> positions(nv);  // relative to `origin`
  std::vector<glm::vec2> texcoords(nvt);
  std::vector<glm::vec3> fileNormals(nvn);
  // Resolved corners, three per triangle (faces fanned). Texture and normal
  // indices are kept only if some face uses them.
  std::vector<uint32_t> cornerV(nc), cornerVt(vtRefs ? nc : 0), cornerVn(vnRefs ? nc : 0);

  // Pass B: parse into place.
  std::atomic<size_t> bytesDone{0};
  const size_t progressStep = 4u << 20;
  std::atomic<size_t> nextReport{progressStep};
  parallelTasks(chunks.size(), threads, [&](size_t k, unsigned worker) {
    Chunk& ch = chunks[k];
    size_t lineNo = ch.line0, v = ch.v0, vt = ch.vt0, vn = ch.vn0, corner = ch.corner0;
    std::vector<Corner> faceCorners;
    const char* reported = ch.begin;
    forEachLine(ch.begin, ch.end, [&](const char* lineBegin, const char* contentEnd, const char*) {
      ++lineNo;
      if (size_t(lineBegin - reported) >= (1u << 20)) {
        const size_t done = bytesDone.fetch_add(size_t(lineBegin - reported)) + size_t(lineBegin - reported);
        reported = lineBegin;
        if (stop || isCancelled(progress)) {
          stop = true;
          return false;
        }
        // Only the calling thread reports (the callback need not be
        // thread-safe), in file-size steps like a single pass would.
        size_t due = nextReport.load();
        if (worker == 0 && done >= due && nextReport.compare_exchange_strong(due, done - done % progressStep + progressStep)) {
          reportProgress(progress, 0.9 * double(done) / double(text.size()), "Reading OBJ");
          if (isCancelled(progress)) {
            stop = true;
            return false;
          }
        }
      }
      Cursor c{lineBegin, contentEnd};
      c.skipSpace();
      if (c.p >= contentEnd || *c.p == '#') return true;
      switch (classify(c.token())) {
        case Key::V: {
          glm::dvec3 p;
          if (!c.number(p.x) || !c.number(p.y) || !c.number(p.z)) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, "cannot read three vertex coordinates");
            return false;
          }
          positions[v] = glm::vec3(v < originVertex ? toZUp(p) : toZUp(p) - origin);
          ++v;
          break;
        }
        case Key::Vt: {
          double u, w = 0.0;
          if (!c.number(u) || (!c.atEnd() && !c.number(w))) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, "cannot read texture coordinate");
            return false;
          }
          // Stored with v = 0 at the image's top row (the order images are read in).
          texcoords[vt++] = glm::vec2(float(u), float(1.0 - w));
          break;
        }
        case Key::Vn: {
          glm::dvec3 n;
          if (!c.number(n.x) || !c.number(n.y) || !c.number(n.z)) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, "cannot read three normal components");
            return false;
          }
          fileNormals[vn++] = glm::vec3(toZUp(n));
          break;
        }
        case Key::F: {
          faceCorners.clear();
          while (!c.atEnd()) {
            Corner cc;
            const std::string_view tok = c.token();
            if (!parseCorner(tok, cc)) {
              ch.error = lineError(lineNo, lineBegin, contentEnd, "cannot read face corner '" + std::string(tok) + "'");
              return false;
            }
            faceCorners.push_back(cc);
          }
          if (faceCorners.size() < 3) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, "a face needs at least 3 corners");
            return false;
          }
          if (faceCorners.size() > 3) ++ch.polygons;
          // Indices resolve against what the file has defined so far, as
          // a single pass sees it. Once a corner is out of range, the rest
          // of the polygon's fan is marked invalid (earlier triangles of it
          // stay), exactly as before.
          bool outOfRange = false;
          auto resolveCorner = [&](const Corner& kc) {
            ComboKey r{resolve(kc.v, v), kc.vt ? resolve(kc.vt, vt) : kAbsent, kc.vn ? resolve(kc.vn, vn) : kAbsent};
            if (r.v == kInvalid || r.vt == kInvalid || r.vn == kInvalid) outOfRange = true;
            ch.anyTexcoordRef |= kc.vt != 0;
            ch.anyNormalRef |= kc.vn != 0;
            return r;
          };
          ComboKey resolved[3];
          resolved[0] = resolveCorner(faceCorners[0]);
          for (size_t i = 1; i + 1 < faceCorners.size(); ++i) {
            resolved[1] = resolveCorner(faceCorners[i]);
            resolved[2] = resolveCorner(faceCorners[i + 1]);
            for (const auto& r : resolved) {
              cornerV[corner] = outOfRange ? kInvalid : r.v;
              if (vtRefs) cornerVt[corner] = outOfRange ? 0 : r.vt;
              if (vnRefs) cornerVn[corner] = outOfRange ? 0 : r.vn;
              ++corner;
            }
          }
          if (outOfRange && !ch.firstOutOfRangeLine) ch.firstOutOfRangeLine = lineNo;
          break;
        }
        case Key::Usemtl:
          c.skipSpace();
          ch.usemtl.push_back({corner, std::string(c.p, contentEnd)});
          break;
        case Key::Mtllib:
          c.skipSpace();
          ch.mtllib.push_back({lineNo, std::string(c.p, contentEnd)});
          break;
        case Key::Skipped:
          ++ch.skipped;  // lines, points and free-form geometry are not meshes
          break;
        default:
          break;
      }
      return true;
    });
    bytesDone.fetch_add(size_t(ch.end - reported));
    if (releaseInput) releasePages(ch.begin, ch.end);
  });
  if (stop && isCancelled(progress)) {
    error = name + ": import cancelled";
    return false;
  }
  std::vector<MtlMaterial> mtl;
  auto readLibraries = [&](const Chunk& ch) {
    for (const auto& lib : ch.mtllib) {
      std::string mtlError;
      const auto path = (std::filesystem::path(baseDir) / lib.name).string();
      if (!readMtl(path, mtl, mtlError))
        report.warnings.push_back(name + ":" + std::to_string(lib.line) + ": " + mtlError);
    }
  };
  for (size_t k = 0; k < chunks.size(); ++k)
    if (!chunks[k].error.empty()) {
      // The first in the file; libraries named before it were read (and
      // their problems reported) by then, as in a single pass.
      for (size_t j = 0; j <= k; ++j) {
        readLibraries(chunks[j]);
        report.polygonsTriangulated += chunks[j].polygons;
        report.skippedLines += chunks[j].skipped;
      }
      error = chunks[k].error;
      return false;
    }

  // Materials, submeshes and messages in file order.
  std::vector<Submesh> submeshes;
  std::unordered_map<std::string, int> materialIndex;  // name -> index in out.materials
  int currentMaterial = -1;
  bool anyTexcoordRef = false, anyNormalRef = false;
  size_t firstOutOfRangeLine = 0;
  // Faces of [from, to) use the current material: a new submesh starts
  // where the material differs from the last submesh's (as a single pass
  // starts one at the first face after such a change).
  auto facesUpTo = [&](size_t from, size_t to) {
    if (to <= from) return;
    if (submeshes.empty() || submeshes.back().material != currentMaterial)
      submeshes.push_back({uint32_t(from), 0, currentMaterial});
  };
  for (const Chunk& ch : chunks) {
    // A chunk's usemtl and mtllib statements interleave with its faces;
    // mtllib only adds definitions, so its position among faces does not
    // matter, only among other mtllib statements and messages.
    size_t at = ch.corner0;
    for (const auto& u : ch.usemtl) {
      facesUpTo(at, u.corner);
      at = u.corner;
      auto it = materialIndex.find(u.name);
      if (it == materialIndex.end()) {
        Material m;
        m.name = u.name;
        it = materialIndex.emplace(u.name, int(out.materials.size())).first;
        out.materials.push_back(m);
      }
      currentMaterial = it->second;
    }
    facesUpTo(at, ch.corner0 + ch.corners);
    readLibraries(ch);
    report.polygonsTriangulated += ch.polygons;
    report.skippedLines += ch.skipped;
    anyTexcoordRef |= ch.anyTexcoordRef;
    anyNormalRef |= ch.anyNormalRef;
    if (!firstOutOfRangeLine) firstOutOfRangeLine = ch.firstOutOfRangeLine;
  }
  for (size_t i = 0; i < submeshes.size(); ++i)
    submeshes[i].indexCount =
        uint32_t((i + 1 < submeshes.size() ? submeshes[i + 1].firstIndex : nc) - submeshes[i].firstIndex);

  report.verticesIn = positions.size();
  report.trianglesIn = nc / 3;
  if (firstOutOfRangeLine)
    report.warnings.push_back(name + ":" + std::to_string(firstOutOfRangeLine) +
                              ": face index out of range (first such face; the file has " +
                              std::to_string(positions.size()) + " vertices)");
  if (report.skippedLines)
    report.warnings.push_back(name + ": " + std::to_string(report.skippedLines) +
                              " line/point/curve statements were skipped (not triangles)");
  if (nc == 0) {
    error = text.empty() ? name + ": file is empty (0 bytes)"
                         : name + ": no faces to import (" + std::to_string(positions.size()) +
                               " vertices, 0 faces)";
    return false;
  }

  // Build output vertices: one per distinct (position, texcoord, normal).
  // Scans without texcoords/normals map positions straight through. The
  // final indices are written over the corner array they are built from.
  reportProgress(progress, 0.9, "Building vertices");
  out.origin = origin;
  if (!anyTexcoordRef && !anyNormalRef) {
    out.positions = std::move(positions);
    out.indices = std::move(cornerV);
  } else {
    std::unordered_map<ComboKey, uint32_t, ComboHash> combos;
    // Most positions have one (texcoord, normal) pair: remember the first
    // and only fall back to the hash map for seams.
    std::vector<uint32_t> first(positions.size(), kInvalid);
    std::vector<ComboKey> outKey;
    outKey.reserve(positions.size());
    for (size_t i = 0; i < nc; ++i) {
      const ComboKey k{cornerV[i], vtRefs ? cornerVt[i] : kAbsent, vnRefs ? cornerVn[i] : kAbsent};
      if (k.v == kInvalid) continue;  // stays kInvalid: sanitize() drops the face
      uint32_t idx = first[k.v];
      if (idx == kInvalid) {
        idx = first[k.v] = uint32_t(outKey.size());
        outKey.push_back(k);
      } else if (!(outKey[idx] == k)) {
        auto [it, inserted] = combos.try_emplace(k, uint32_t(outKey.size()));
        if (inserted) outKey.push_back(k);
        idx = it->second;
      }
      cornerV[i] = idx;
    }
    cornerVt = {};
    cornerVn = {};
    first = {};
    combos = {};
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
    out.indices = std::move(cornerV);
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
    // Kd is a reflectance, taken as linear RGB as it is written: what
    // Blender's OBJ importer and exporter do, and what Assimp's OBJ reader
    // gives, so an OBJ has the same colours through either reader.
    m.baseColor = glm::vec4(src->kd, src->opacity);
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
