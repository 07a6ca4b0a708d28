#include "mesh/import_wire.h"

#include <sys/stat.h>

#include <cinttypes>
#include <cstring>

#include "mesh/mesh_geometry_codec.h"

namespace hs::mesh {
namespace {

constexpr char kMagic[8] = {'H', 'S', 'I', 'M', 'P', 'R', 'E', 'S'};
constexpr char kTrailer[8] = {'H', 'S', 'I', 'M', 'P', 'E', 'N', 'D'};
constexpr uint32_t kVersion = 2;  // 2: declared triangles in the report

struct ResultWriter {
  std::FILE* f;
  bool ok = true;
  void raw(const void* p, size_t n) {
    if (ok && n && std::fwrite(p, 1, n, f) != n) ok = false;
  }
  template <class T>
  void pod(const T& v) { raw(&v, sizeof v); }
  void str(const std::string& s) {
    pod(uint64_t(s.size()));
    raw(s.data(), s.size());
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    pod(uint64_t(v.size()));
    raw(v.data(), v.size() * sizeof(T));
  }
};

struct ResultReader {
  std::FILE* f;
  uint64_t left;  // bytes from the current position to the end of the file
  std::string& error;
  bool ok = true;

  bool fail(const std::string& why) {
    if (ok) error = why;
    ok = false;
    return false;
  }
  bool raw(void* p, uint64_t n, const char* field) {
    if (!ok) return false;
    if (n > left) return fail(std::string("the result is cut short (reading ") + field + ")");
    if (n && std::fread(p, 1, size_t(n), f) != n) return fail(std::string("the result could not be read (") + field + ")");
    left -= n;
    return true;
  }
  template <class T>
  T pod(const char* field) {
    T v{};
    raw(&v, sizeof v, field);
    return v;
  }
  std::string str(const char* field) {
    const uint64_t n = pod<uint64_t>(field);
    if (!ok) return {};
    if (n > left) {
      fail(std::string("the result is cut short (reading ") + field + ")");
      return {};
    }
    std::string s(static_cast<size_t>(n), '\0');
    raw(s.data(), n, field);
    return s;
  }
  template <class T>
  std::vector<T> vec(const char* field) {
    const uint64_t n = pod<uint64_t>(field);
    if (!ok) return {};
    if (n > left / sizeof(T)) {
      fail(std::string("the result is cut short (reading ") + field + ")");
      return {};
    }
    std::vector<T> v(static_cast<size_t>(n));
    raw(v.data(), n * sizeof(T), field);
    return v;
  }
};

void writeReport(ResultWriter& w, const mesh::ImportReport& r) {
  w.str(r.file);
  w.str(r.reader);
  for (size_t v : {r.verticesIn, r.trianglesIn, r.verticesOut, r.trianglesOut, r.nonFiniteVertices, r.outOfRangeFaces,
                   r.degenerateFaces, r.polygonsTriangulated, r.skippedLines})
    w.pod(uint64_t(v));
  w.pod(uint8_t(r.normalsGenerated));
  w.pod(uint8_t(r.upAxisConverted));
  w.pod(uint64_t(r.warnings.size()));
  for (const auto& s : r.warnings) w.str(s);
  w.pod(r.seconds);
  w.pod(r.geoOffset);
  w.str(r.geoOffsetSource);
  w.str(r.geoOffsetCrs);
  w.pod(uint64_t(r.declaredTriangles));
  w.str(r.declaredBy);
}

void readReport(ResultReader& rd, mesh::ImportReport& r) {
  r.file = rd.str("report");
  r.reader = rd.str("report");
  for (size_t* v : {&r.verticesIn, &r.trianglesIn, &r.verticesOut, &r.trianglesOut, &r.nonFiniteVertices,
                    &r.outOfRangeFaces, &r.degenerateFaces, &r.polygonsTriangulated, &r.skippedLines})
    *v = size_t(rd.pod<uint64_t>("report counts"));
  r.normalsGenerated = rd.pod<uint8_t>("report") != 0;
  r.upAxisConverted = rd.pod<uint8_t>("report") != 0;
  const uint64_t nWarnings = rd.pod<uint64_t>("warnings");
  for (uint64_t i = 0; rd.ok && i < nWarnings; ++i) r.warnings.push_back(rd.str("warnings"));
  r.seconds = rd.pod<double>("report");
  r.geoOffset = rd.pod<glm::dvec3>("report");
  r.geoOffsetSource = rd.str("report");
  r.geoOffsetCrs = rd.str("report");
  r.declaredTriangles = size_t(rd.pod<uint64_t>("report"));
  r.declaredBy = rd.str("report");
}

void writeMesh(ResultWriter& w, const mesh::MeshData& m) {
  writeMeshGeometry(w, m);
  // Both the source bytes and the decoded pixels: decoding again here would
  // cost as much as the worker's decoding did.
  w.pod(uint64_t(m.textures.size()));
  for (const auto& t : m.textures) {
    w.str(t.name);
    w.pod(int32_t(t.width));
    w.pod(int32_t(t.height));
    w.vec(t.encoded);
    w.vec(t.rgba);
  }
}

bool readMesh(ResultReader& rd, mesh::MeshData& m) {
  readMeshGeometry(rd, m);
  const uint64_t nTextures = rd.pod<uint64_t>("texture count");
  for (uint64_t i = 0; rd.ok && i < nTextures; ++i) {
    mesh::Texture t;
    t.name = rd.str("texture name");
    t.width = rd.pod<int32_t>("texture width");
    t.height = rd.pod<int32_t>("texture height");
    t.encoded = rd.vec<uint8_t>("texture bytes");
    t.rgba = rd.vec<uint8_t>("texture pixels");
    if (rd.ok && (t.width < 0 || t.height < 0 || t.rgba.size() != size_t(t.width) * size_t(t.height) * 4))
      return rd.fail("texture '" + t.name + "' has the wrong number of pixels");
    m.textures.push_back(std::move(t));
  }
  if (!rd.ok) return false;
  const size_t nv = m.positions.size();
  if (m.normals.size() != nv || (!m.uvs.empty() && m.uvs.size() != nv))
    return rd.fail("vertex arrays have different lengths");
  if (m.indices.size() % 3 != 0) return rd.fail("index count is not a multiple of 3");
  for (uint32_t idx : m.indices)
    if (idx >= nv) return rd.fail("an index is past the vertices");
  for (const auto& s : m.submeshes)
    if (uint64_t(s.firstIndex) + s.indexCount > m.indices.size() || s.material >= int(m.materials.size()))
      return rd.fail("a submesh range or material is out of bounds");
  for (const auto& mat : m.materials)
    if (mat.diffuseTexture >= int(m.textures.size())) return rd.fail("a material's texture index is out of bounds");
  return true;
}

const char* upName(mesh::UpAxis u) { return u == mesh::UpAxis::Y ? "y" : u == mesh::UpAxis::Z ? "z" : "auto"; }
const char* readerName(mesh::Reader r) {
  return r == mesh::Reader::Obj ? "obj" : r == mesh::Reader::Assimp ? "assimp" : "auto";
}
const char* originModeName(mesh::ImportOptions::GeoOffsetMode m) {
  using M = mesh::ImportOptions::GeoOffsetMode;
  return m == M::Auto ? "auto" : m == M::File ? "file" : m == M::Manual ? "manual" : "none";
}

}  // namespace

std::vector<std::string> importWorkerArguments(const std::string& path, const mesh::ImportOptions& o) {
  char origin[128];
  std::snprintf(origin, sizeof origin, "%.17g,%.17g,%.17g", o.geoOffset.x, o.geoOffset.y, o.geoOffset.z);
  return {"--up",          upName(o.up),
          "--reader",      readerName(o.reader),
          "--recenter",    o.recenter ? "1" : "0",
          "--strict-textures", o.strictTextures ? "1" : "0",
          "--strict",      o.strict ? "1" : "0",
          "--origin-mode", originModeName(o.geoOffsetMode),
          "--origin-file", o.geoOffsetFile,
          "--origin",      origin,
          "--",            path};
}

bool parseImportWorkerOptionArgument(const std::string& key, const std::string& value, mesh::ImportOptions& o,
                                     std::string& error) {
  using M = mesh::ImportOptions::GeoOffsetMode;
  auto flag = [&](bool& b) {
    if (value != "0" && value != "1") return false;
    b = value == "1";
    return true;
  };
  bool ok = true;
  if (key == "--up") {
    if (value == "auto") o.up = mesh::UpAxis::Auto;
    else if (value == "y") o.up = mesh::UpAxis::Y;
    else if (value == "z") o.up = mesh::UpAxis::Z;
    else ok = false;
  } else if (key == "--reader") {
    if (value == "auto") o.reader = mesh::Reader::Auto;
    else if (value == "obj") o.reader = mesh::Reader::Obj;
    else if (value == "assimp") o.reader = mesh::Reader::Assimp;
    else ok = false;
  } else if (key == "--recenter") {
    ok = flag(o.recenter);
  } else if (key == "--strict-textures") {
    ok = flag(o.strictTextures);
  } else if (key == "--strict") {
    ok = flag(o.strict);
  } else if (key == "--origin-mode") {
    if (value == "none") o.geoOffsetMode = M::None;
    else if (value == "auto") o.geoOffsetMode = M::Auto;
    else if (value == "file") o.geoOffsetMode = M::File;
    else if (value == "manual") o.geoOffsetMode = M::Manual;
    else ok = false;
  } else if (key == "--origin-file") {
    o.geoOffsetFile = value;
  } else if (key == "--origin") {
    double x, y, z;
    char end;
    ok = std::sscanf(value.c_str(), "%lf,%lf,%lf%c", &x, &y, &z, &end) == 3;
    if (ok) o.geoOffset = glm::dvec3(x, y, z);
  } else {
    error = "unknown option " + key;
    return false;
  }
  if (!ok) error = key + ": bad value '" + value + "'";
  return ok;
}

std::string importRequest(const std::vector<std::string>& args) {
  std::string out = "request " + std::to_string(args.size()) + "\n";
  for (const std::string& a : args) out += std::to_string(a.size()) + "\n" + a + "\n";
  return out;
}

bool readImportRequest(std::FILE* in, std::vector<std::string>& args, std::string& error) {
  error.clear();
  args.clear();
  unsigned long count = 0;
  const int got = std::fscanf(in, "request %lu", &count);
  if (got == EOF) return false;
  // Bounded: a request has a dozen arguments, each a path or a number.
  if (got != 1 || std::fgetc(in) != '\n' || count > 1000) {
    error = "a malformed request";
    return false;
  }
  for (unsigned long i = 0; i < count; ++i) {
    unsigned long length = 0;
    if (std::fscanf(in, "%lu", &length) != 1 || std::fgetc(in) != '\n' || length > (1ul << 20)) {
      error = "a malformed request (argument " + std::to_string(i + 1) + ")";
      return false;
    }
    std::string a(length, '\0');
    if ((length > 0 && std::fread(a.data(), 1, length, in) != length) || std::fgetc(in) != '\n') {
      error = "a request cut short (argument " + std::to_string(i + 1) + ")";
      return false;
    }
    args.push_back(std::move(a));
  }
  return true;
}

std::string importProgressLine(double fraction, std::string_view stage) {
  char head[64];
  std::snprintf(head, sizeof head, "progress %.4f ", fraction);
  std::string line = head;
  for (char c : stage) line += (c == '\n' || c == '\r') ? ' ' : c;
  line += '\n';
  return line;
}

bool parseImportProgressLine(std::string_view line, double& fraction, std::string& stage) {
  constexpr std::string_view kHead = "progress ";
  if (line.substr(0, kHead.size()) != kHead) return false;
  const std::string rest(line.substr(kHead.size()));
  int used = 0;
  if (std::sscanf(rest.c_str(), "%lf %n", &fraction, &used) < 1) return false;
  stage = rest.substr(size_t(used));
  while (!stage.empty() && (stage.back() == '\n' || stage.back() == '\r')) stage.pop_back();
  return true;
}

bool writeImportResult(std::FILE* out, const mesh::ImportResult& r) {
  ResultWriter w{out};
  w.raw(kMagic, sizeof kMagic);
  w.pod(kVersion);
  w.pod(uint8_t(r.mesh.has_value()));
  w.pod(uint8_t(r.cancelled));
  w.str(r.error);
  writeReport(w, r.report);
  if (r.mesh) writeMesh(w, *r.mesh);
  w.raw(kTrailer, sizeof kTrailer);
  return w.ok && std::fflush(out) == 0;
}

bool readImportResult(std::FILE* in, mesh::ImportResult& result, std::string& error) {
  struct stat st {};
  if (fstat(fileno(in), &st) != 0) {
    error = "the result could not be read";
    return false;
  }
  std::rewind(in);
  ResultReader rd{in, uint64_t(st.st_size), error};
  if (st.st_size == 0) return rd.fail("no result was written");
  char magic[8];
  rd.raw(magic, sizeof magic, "header");
  if (rd.ok && std::memcmp(magic, kMagic, sizeof magic) != 0) return rd.fail("the result has a bad header");
  const uint32_t version = rd.pod<uint32_t>("header");
  if (rd.ok && version != kVersion)
    return rd.fail("the result is of version " + std::to_string(version) + ", not " + std::to_string(kVersion) +
                   " (worker and program are from different builds)");
  mesh::ImportResult r;
  const bool hasMesh = rd.pod<uint8_t>("header") != 0;
  r.cancelled = rd.pod<uint8_t>("header") != 0;
  r.error = rd.str("error");
  readReport(rd, r.report);
  if (hasMesh && rd.ok) {
    mesh::MeshData m;
    if (readMesh(rd, m)) r.mesh = std::move(m);
  }
  char trailer[8];
  rd.raw(trailer, sizeof trailer, "trailer");
  if (rd.ok && std::memcmp(trailer, kTrailer, sizeof trailer) != 0) return rd.fail("the result has a bad trailer");
  if (!rd.ok) return false;
  result = std::move(r);
  return true;
}

}  // namespace hs::mesh
