#include "mesh/obj_reader.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "core/parallel.h"
#include "mesh/line_blocks.h"
#include "mesh/mtl_reader.h"
#include "mesh/texture_decode.h"

// How the reader scales (photogrammetry OBJs run to gigabytes):
//   1. the file is cut into chunks at line starts;
//   2. pass A, in parallel: each chunk is read (pread, 256 kB at a time,
//      into its worker's buffer: line_blocks.h) and counts its lines and
//      its v, vt, vn and triangle corners (a cheap scan; only its first
//      vertex is parsed, for the origin);
//   3. prefix sums give every chunk the line number, vertex numbers and
//      corner offset it starts at, and the output arrays are allocated once
//      at their final size;
//   4. pass B, in parallel: each chunk is read again and parses its lines
//      straight into those arrays at its offsets, resolving face indices
//      (absolute and relative) against the global counts it now knows;
//   5. serially: materials, submeshes, messages in file order, then the
//      vertex build, which writes the final indices over the corner array.
// No per-chunk copies are merged, so memory stays near the final mesh plus
// a 256 kB piece of the file per worker. The file is read, not mapped: a
// mapped file that shrinks kills the process with SIGBUS, while here a
// short read, a chunk that counts differently the second time, or a size
// or time that changed by the end is an error naming the file
// (byte_source.h). The price is the kernel copying the file into the
// buffers, once per pass: about 5% more CPU time for the whole import than
// mapping (bench/decimate/README.md). Results, messages and line numbers
// are the same for any number of threads, and the same as a single pass.

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
  // Inlined by force, as parseCorner: they run for every number of the
  // file, and GCC 12 stops inlining them into the line parser once it
  // grows a little (8% more instructions for the whole import, callgrind).
  [[gnu::always_inline]] bool number(double& v) {
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

[[gnu::always_inline]] inline bool parseCorner(std::string_view tok, Corner& c) {
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

// Calls fn(lineBegin, contentEnd, terminated) for every line of [begin,
// end); contentEnd excludes the line end and a '\r' before it, and only the
// last line can lack a line end (terminated false). Returns false when fn
// stopped it by returning false.
template <class Fn>
bool forEachLine(const char* begin, const char* end, Fn&& fn) {
  for (const char* p = begin; p < end;) {
    const char* nl = static_cast<const char*>(memchr(p, '\n', size_t(end - p)));
    const char* contentEnd = nl ? nl : end;
    if (contentEnd > p && contentEnd[-1] == '\r') --contentEnd;
    if (!fn(p, contentEnd, nl != nullptr)) return false;
    p = nl ? nl + 1 : end;
  }
  return true;
}

struct Chunk {
  uint64_t begin = 0, end = 0;  // byte offsets in the file
  // Pass A: what the chunk holds.
  size_t newlines = 0, v = 0, vt = 0, vn = 0, corners = 0;
  bool vtRefs = false, vnRefs = false;
  // The chunk's first vertex, for the provisional origin: whether one was
  // read (finite, or malformed, which pass B reports), how many NaN/Inf
  // vertices came before it in the chunk, and the rounded position.
  enum class FirstVertex : uint8_t { NotYet, Finite, Malformed } firstVertex = FirstVertex::NotYet;
  size_t nonFiniteBefore = 0;
  glm::dvec3 firstFinite{0.0};
  // Where it starts in the file (prefix sums of the above).
  size_t line0 = 0, v0 = 0, vt0 = 0, vn0 = 0, corner0 = 0;
  // Pass B: what happened, merged in file order afterwards.
  std::string error;  // first fatal problem (messages name the line)
  size_t firstOutOfRangeLine = 0;
  size_t polygons = 0, skipped = 0;
  bool anyTexcoordRef = false, anyNormalRef = false;
  size_t unterminatedLine = 0;  // the file's last line, when it has no line end
  std::string unterminatedText;
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

// Cuts [0, size) into chunks of about `target` bytes that end after a line
// end (or at the end of the file); only the bytes around each cut are read.
bool cutChunks(const ByteSource& source, uint64_t target, std::vector<Chunk>& chunks, std::string& error) {
  const uint64_t size = source.size();
  std::string buffer;
  std::string_view window;
  uint64_t p = 0;
  do {
    Chunk ch;
    ch.begin = p;
    uint64_t cut = p + std::min(target, size - p);
    while (cut < size) {
      if (!source.read(cut, 64 << 10, buffer, window, error)) return false;
      if (const void* nl = memchr(window.data(), '\n', window.size())) {
        cut += uint64_t(static_cast<const char*>(nl) - window.data()) + 1;
        break;
      }
      cut += window.size();
    }
    ch.end = std::min(cut, size);
    chunks.push_back(std::move(ch));
    p = chunks.back().end;
  } while (p < size);
  return true;
}

// The cold paths of the line parsers, kept out of them so they stay small
// (see Cursor::number).

[[gnu::noinline, gnu::cold]] void noteChanged(Chunk& ch, const std::string& name, size_t lineNo) {
  ch.error = name + ":" + std::to_string(lineNo) +
             ": the file changed while it was read (this part holds other statements than it did a moment "
             "before); read it again once whatever writes it has finished";
}

[[gnu::noinline, gnu::cold]] void noteUnterminated(Chunk& ch, size_t lineNo, const char* begin, const char* end) {
  ch.unterminatedLine = lineNo;
  ch.unterminatedText.assign(begin, std::min<size_t>(size_t(end - begin), 60));
}

// The chunk's first vertex, for the provisional origin (`c` is past "v").
template <class ToZUp>
[[gnu::noinline, gnu::cold]] void noteFirstVertex(Chunk& ch, Cursor c, const ToZUp& toZUp) {
  glm::dvec3 v;
  if (!c.number(v.x) || !c.number(v.y) || !c.number(v.z)) {
    ch.firstVertex = Chunk::FirstVertex::Malformed;
  } else if (v = toZUp(v); std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) {
    ch.firstVertex = Chunk::FirstVertex::Finite;
    ch.firstFinite = glm::round(v);
  } else {
    ++ch.nonFiniteBefore;
  }
}

}  // namespace

bool readObj(const ByteSource& source, const std::string& baseDir, const ImportOptions& options,
             const Progress* progress, MeshData& out, ImportReport& report, std::string& error) {
  const std::string& name = source.name();
  const uint64_t size = source.size();
  // A binary file (a renamed image, an FBX) is not an OBJ: say so instead of
  // reporting the first garbage line as malformed.
  {
    std::string buffer;
    std::string_view head;
    if (!source.read(0, 4096, buffer, head, error)) return false;
    // An empty view may have no data pointer, which memchr must not get.
    if (const void* zero = head.empty() ? nullptr : memchr(head.data(), '\0', head.size())) {
      error = name + ": not a text OBJ file (binary data at byte " +
              std::to_string(static_cast<const char*>(zero) - head.data()) + ")";
      return false;
    }
  }

  const bool zUp = options.up == UpAxis::Z;  // OBJ declares no axis: Y-up unless told
  report.upAxisConverted = !zUp;
  auto toZUp = [zUp](glm::dvec3 p) { return zUp ? p : glm::dvec3(p.x, -p.z, p.y); };

  // `unterminated`: the line is the file's last and has no line end.
  auto lineError = [&](size_t lineNo, const char* lineBegin, const char* lineEnd, bool unterminated,
                       const std::string& what) {
    std::string shown(lineBegin, std::min<size_t>(size_t(lineEnd - lineBegin), 60));
    if (unterminated)
      return name + ":" + std::to_string(lineNo) +
             ": file is truncated: the last line stops in the middle of a statement ('" + shown + "')";
    return name + ":" + std::to_string(lineNo) + ": " + what + " ('" + shown + "')";
  };

  // Chunks: about eight per worker so uneven chunks balance, never smaller
  // than 4 MB (a small file is one chunk, read exactly like a single pass).
  // A worker reads its chunk a piece at a time into its own buffer, once
  // per pass (line_blocks.h), so it holds ~256 kB of the file, not a chunk.
  const unsigned threads = resolveThreads(0);
  const uint64_t target = std::max<uint64_t>(uint64_t(4) << 20, size / (uint64_t(threads) * 8) + 1);
  std::vector<Chunk> chunks;
  if (!cutChunks(source, target, chunks, error)) return false;
  std::vector<std::string> buffers(threads);

  // Pass A: counts.
  std::atomic<bool> stop{false};
  parallelTasks(chunks.size(), threads, [&](size_t k, unsigned slot) {
    if (stop) return;
    Chunk& ch = chunks[k];
    auto countLine = [&](const char* b, const char* ce, bool terminated) {
      ch.newlines += terminated;
      Cursor c{b, ce};
      c.skipSpace();
      if (c.p >= ce || *c.p == '#') return true;
      switch (classify(c.token())) {
        case Key::V:
          // The provisional origin needs the first finite vertex of the
          // file: each chunk finds its own first one.
          if (ch.firstVertex == Chunk::FirstVertex::NotYet) [[unlikely]]
            noteFirstVertex(ch, c, toZUp);
          ++ch.v;
          break;
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
    };
    const bool read = forEachLineBlock(source, ch.begin, ch.end, buffers[slot], ch.error, [&](std::string_view piece) {
      forEachLine(piece.data(), piece.data() + piece.size(), countLine);
      return !isCancelled(progress);
    });
    if (!read || isCancelled(progress)) stop = true;
  });
  for (const Chunk& ch : chunks)
    if (!ch.error.empty()) {  // the file could not be read
      error = ch.error;
      return false;
    }
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
  // Provisional origin: the first finite vertex, rounded, keeps floats small
  // from the first vertex on, so UTM coordinates never pass through single
  // precision. Vertices before it (NaN/Inf) are stored as read; a malformed
  // first vertex leaves it at 0 (pass B reports the line).
  glm::dvec3 origin(0.0);
  size_t originVertex = SIZE_MAX;
  for (const Chunk& ch : chunks) {
    if (ch.firstVertex == Chunk::FirstVertex::Malformed) break;
    if (ch.firstVertex == Chunk::FirstVertex::Finite) {
      origin = ch.firstFinite;
      originVertex = ch.v0 + ch.nonFiniteBefore;  // every vertex before this chunk was NaN/Inf
      break;
    }
  }
  std::vector<glm::vec3> positions(nv);  // relative to `origin`
  std::vector<glm::vec2> texcoords(nvt);
  std::vector<glm::vec3> fileNormals(nvn);
  // Resolved corners, three per triangle (faces fanned). Texture and normal
  // indices are kept only if some face uses them.
  std::vector<uint32_t> cornerV(nc), cornerVt(vtRefs ? nc : 0), cornerVn(vnRefs ? nc : 0);

  // Pass B: parse into place. The chunk is read again: if the file changed
  // since pass A counted it, the counts no longer hold, and the chunk stops
  // before writing past the space pass A gave it.
  std::atomic<size_t> bytesDone{0};
  const size_t progressStep = 4u << 20;
  std::atomic<size_t> nextReport{progressStep};
  parallelTasks(chunks.size(), threads, [&](size_t k, unsigned worker) {
    Chunk& ch = chunks[k];
    if (stop) return;
    size_t lineNo = ch.line0, v = ch.v0, vt = ch.vt0, vn = ch.vn0, corner = ch.corner0;
    auto changed = [&]() {
      noteChanged(ch, name, lineNo);
      stop = true;
      return false;
    };
    std::vector<Corner> faceCorners;
    auto parseLine = [&](const char* lineBegin, const char* contentEnd, bool terminated) {
      ++lineNo;
      // Only the file's last line can end without a line end (chunks end
      // after one).
      const bool unterminated = !terminated;
      Cursor c{lineBegin, contentEnd};
      c.skipSpace();
      if (unterminated && c.p < contentEnd) [[unlikely]]
        noteUnterminated(ch, lineNo, lineBegin, contentEnd);
      if (c.p >= contentEnd || *c.p == '#') return true;
      switch (classify(c.token())) {
        case Key::V: {
          if (v >= ch.v0 + ch.v) [[unlikely]] return changed();
          glm::dvec3 p;
          if (!c.number(p.x) || !c.number(p.y) || !c.number(p.z)) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, unterminated, "cannot read three vertex coordinates");
            return false;
          }
          positions[v] = glm::vec3(v < originVertex ? toZUp(p) : toZUp(p) - origin);
          ++v;
          break;
        }
        case Key::Vt: {
          if (vt >= ch.vt0 + ch.vt) [[unlikely]] return changed();
          double u, w = 0.0;
          if (!c.number(u) || (!c.atEnd() && !c.number(w))) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, unterminated, "cannot read texture coordinate");
            return false;
          }
          // Stored with v = 0 at the image's top row (the order images are read in).
          texcoords[vt++] = glm::vec2(float(u), float(1.0 - w));
          break;
        }
        case Key::Vn: {
          if (vn >= ch.vn0 + ch.vn) [[unlikely]] return changed();
          glm::dvec3 n;
          if (!c.number(n.x) || !c.number(n.y) || !c.number(n.z)) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, unterminated, "cannot read three normal components");
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
              ch.error = lineError(lineNo, lineBegin, contentEnd, unterminated,
                                   "cannot read face corner '" + std::string(tok) + "'");
              return false;
            }
            faceCorners.push_back(cc);
          }
          if (faceCorners.size() < 3) {
            ch.error = lineError(lineNo, lineBegin, contentEnd, unterminated, "a face needs at least 3 corners");
            return false;
          }
          if (corner + (faceCorners.size() - 2) * 3 > ch.corner0 + ch.corners) [[unlikely]] return changed();
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
    };
    const bool read = forEachLineBlock(source, ch.begin, ch.end, buffers[worker], ch.error, [&](std::string_view piece) {
      if (!forEachLine(piece.data(), piece.data() + piece.size(), parseLine)) return false;
      const size_t done = bytesDone.fetch_add(piece.size()) + piece.size();
      if (stop || isCancelled(progress)) {
        stop = true;
        return false;
      }
      // Only the calling thread reports (the callback need not be
      // thread-safe), in file-size steps like a single pass would.
      size_t due = nextReport.load();
      if (worker == 0 && done >= due && nextReport.compare_exchange_strong(due, done - done % progressStep + progressStep)) {
        reportProgress(progress, 0.9 * double(done) / double(size), "Reading OBJ");
        if (isCancelled(progress)) {
          stop = true;
          return false;
        }
      }
      return true;
    });
    if (!read) {
      stop = true;
      return;
    }
    // Fewer statements than pass A counted: the rest of the chunk's space
    // would stay unwritten.
    if (ch.error.empty() && !stop && (v != ch.v0 + ch.v || vt != ch.vt0 + ch.vt || vn != ch.vn0 + ch.vn ||
                                      corner != ch.corner0 + ch.corners))
      changed();
  });
  buffers = {};
  if (stop && isCancelled(progress)) {
    error = name + ": import cancelled";
    return false;
  }
  // Written to while we read it: whatever a chunk found may mix two
  // versions of the file, so say that rather than what they found.
  if (!source.unchanged(error)) return false;
  std::vector<MtlMaterial> mtl;
  auto readLibraries = [&](const Chunk& ch) {
    for (const auto& lib : ch.mtllib) {
      std::string mtlError;
      const auto path = (std::filesystem::path(baseDir) / lib.name).string();
      std::vector<std::string> mtlWarnings;
      if (!readMtl(path, mtl, mtlError, &mtlWarnings))
        report.warnings.push_back(name + ":" + std::to_string(lib.line) + ": " + mtlError);
      for (auto& w : mtlWarnings) report.warnings.push_back(std::move(w));
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
    // A file cut short mid-line can still parse (`v 1 2 3.25` cut to
    // `v 1 2 3.`), so a missing final line end is said, never silent.
    if (ch.unterminatedLine)
      report.warnings.push_back(name + ":" + std::to_string(ch.unterminatedLine) +
                                ": the file does not end with a line end, so it may have been cut short; its last "
                                "line ('" + ch.unterminatedText + "') was read as it stands");
  }
  for (size_t i = 0; i < submeshes.size(); ++i)
    submeshes[i].indexCount =
        uint32_t((i + 1 < submeshes.size() ? submeshes[i + 1].firstIndex : nc) - submeshes[i].firstIndex);

  report.verticesIn = positions.size();
  report.trianglesIn = nc / 3;
  // OBJ declares no counts: what it declares is the faces it holds.
  report.declaredTriangles = report.trianglesIn;
  report.declaredBy = "OBJ faces";
  if (firstOutOfRangeLine)
    report.warnings.push_back(name + ":" + std::to_string(firstOutOfRangeLine) +
                              ": face index out of range (first such face; the file has " +
                              std::to_string(positions.size()) + " vertices)");
  if (report.skippedLines)
    report.warnings.push_back(name + ": " + std::to_string(report.skippedLines) +
                              " line/point/curve statements were skipped (not triangles)");
  if (nc == 0) {
    error = size == 0 ? name + ": file is empty (0 bytes)"
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
      std::string texError, texNote;
      reportProgress(progress, 0.92, "Loading textures");
      if (decodeTextureFile(texPath, tex, texError, &texNote)) {
        if (!texNote.empty()) report.warnings.push_back(name + ": material '" + m.name + "': " + texNote);
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
