#include "scene/mesh_blob.h"

#include <algorithm>

#include <cstring>

#include "mesh/mesh_geometry_codec.h"
#include "mesh/texture_decode.h"

namespace hs::scene {
namespace {

constexpr char kMagic[8] = {'H', 'S', 'M', 'E', 'S', 'H', '\0', '\1'};
constexpr uint32_t kVersion = 1;

struct Writer {
  std::vector<uint8_t> out;
  void raw(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
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
    if (!v.empty()) raw(v.data(), v.size() * sizeof(T));
  }
};

struct Reader {
  const uint8_t* data;
  size_t size;
  size_t pos = 0;
  const std::string& what;
  std::string& error;
  bool ok = true;

  bool need(size_t n, const char* field) {
    if (!ok) return false;
    if (n > size - pos) {
      error = what + ": data is truncated at byte " + std::to_string(pos) + " (reading " + field +
              ", needs " + std::to_string(n) + " bytes, " + std::to_string(size - pos) + " left)";
      ok = false;
    }
    return ok;
  }
  template <class T>
  T pod(const char* field) {
    T v{};
    if (need(sizeof(T), field)) {
      std::memcpy(&v, data + pos, sizeof(T));
      pos += sizeof(T);
    }
    return v;
  }
  std::string str(const char* field) {
    const uint64_t n = pod<uint64_t>(field);
    if (!need(n, field)) return {};
    std::string s(reinterpret_cast<const char*>(data + pos), n);
    pos += n;
    return s;
  }
  template <class T>
  std::vector<T> vec(const char* field) {
    const uint64_t n = pod<uint64_t>(field);
    if (!ok) return {};
    if (n > (size - pos) / sizeof(T)) {
      need(size - pos + 1, field);  // reports truncation
      return {};
    }
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), data + pos, n * sizeof(T));
    pos += n * sizeof(T);
    return v;
  }
};

}  // namespace

std::vector<uint8_t> encodeMesh(const mesh::MeshData& m) {
  Writer w;
  w.out.reserve(64 + m.memoryBytes());
  w.raw(kMagic, sizeof kMagic);
  w.pod(kVersion);
  writeMeshGeometry(w, m);
  w.pod(uint64_t(m.textures.size()));
  for (const auto& t : m.textures) {
    w.str(t.name);
    // The source file's bytes when there were any (compact); raw pixels otherwise.
    const bool encoded = !t.encoded.empty();
    w.pod(uint8_t(encoded));
    w.pod(int32_t(t.width));
    w.pod(int32_t(t.height));
    w.vec(encoded ? t.encoded : t.rgba);
  }
  return std::move(w.out);
}

std::optional<mesh::MeshData> decodeMesh(const uint8_t* data, size_t size, const std::string& what,
                                         std::string& error, size_t baseTextures) {
  Reader r{data, size, 0, what, error};
  char magic[8];
  if (!r.need(sizeof magic, "header")) return std::nullopt;
  std::memcpy(magic, data, sizeof magic);
  r.pos = sizeof magic;
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) {
    error = what + ": not a mesh blob (bad magic bytes)";
    return std::nullopt;
  }
  const uint32_t version = r.pod<uint32_t>("version");
  if (r.ok && version > kVersion) {
    error = what + ": mesh data version " + std::to_string(version) + " is newer than this build reads (" +
            std::to_string(kVersion) + ")";
    return std::nullopt;
  }
  mesh::MeshData m;
  readMeshGeometry(r, m);
  const uint64_t nTextures = r.pod<uint64_t>("texture count");
  for (uint64_t i = 0; r.ok && i < nTextures; ++i) {
    mesh::Texture t;
    t.name = r.str("texture name");
    const bool encoded = r.pod<uint8_t>("texture kind") != 0;
    t.width = r.pod<int32_t>("texture width");
    t.height = r.pod<int32_t>("texture height");
    auto bytes = r.vec<uint8_t>("texture data");
    if (!r.ok) break;
    if (encoded) {
      t.encoded = std::move(bytes);
      std::string texError;
      if (!mesh::decodeTextureInPlace(t, texError)) {
        error = what + ": " + texError;
        return std::nullopt;
      }
    } else {
      if (t.width < 0 || t.height < 0 || bytes.size() != size_t(t.width) * size_t(t.height) * 4) {
        error = what + ": texture '" + t.name + "' has " + std::to_string(bytes.size()) +
                " bytes for " + std::to_string(t.width) + "x" + std::to_string(t.height) + " RGBA pixels";
        return std::nullopt;
      }
      t.rgba = std::move(bytes);
    }
    m.textures.push_back(std::move(t));
  }
  if (!r.ok) return std::nullopt;

  // Cross-checks: sizes agree and every index points at a vertex.
  const size_t nv = m.positions.size();
  auto bad = [&](const std::string& why) {
    error = what + ": " + why;
    return std::nullopt;
  };
  if (m.normals.size() != nv || (!m.uvs.empty() && m.uvs.size() != nv))
    return bad("vertex arrays have different lengths");
  if (m.indices.size() % 3 != 0) return bad("index count is not a multiple of 3");
  for (uint32_t idx : m.indices)
    if (idx >= nv) return bad("index " + std::to_string(idx) + " is past the " + std::to_string(nv) + " vertices");
  for (const auto& s : m.submeshes)
    if (uint64_t(s.firstIndex) + s.indexCount > m.indices.size() ||
        s.material >= int(m.materials.size()))
      return bad("a submesh range or material is out of bounds");
  for (const auto& mat : m.materials)
    if (mat.diffuseTexture >= int(std::max(m.textures.size(), baseTextures)))
      return bad("a material's texture index is out of bounds");
  return m;
}

}  // namespace hs::scene
