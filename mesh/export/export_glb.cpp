// glTF 2.0 binary (GLB), written directly: a JSON chunk and a BIN chunk.
// A small writer rather than Assimp's exporter: the scene would have to be
// rebuilt as an aiScene (float matrices, so a UTM translation would lose
// its metres), and the format is a few hundred lines of specification.
// Y-up by specification; positions relative to the placed origin as float;
// with `world` the origin becomes the node's translation (JSON numbers:
// doubles). UVs as MeshData holds them (top-left origin, as glTF). One primitive per
// submesh, sharing the vertex arrays; or, with Draco (o.dracoBits), one
// Draco bitstream per submesh holding the vertices it uses, its accessors
// without buffer views as KHR_draco_mesh_compression has them.
#include <algorithm>
#include <cstring>
#include <limits>

#include "core/json.h"
#include "mesh/export/draco_encode.h"
#include "mesh/export/export_geometry.h"

namespace hs::mesh::exporting {

namespace {

constexpr uint32_t kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr uint32_t kFloat = 5126, kUnsignedInt = 5125;

struct Bin {
  std::string bytes;
  Json views = Json::array();
  // A buffer view over `data`, aligned to 4 bytes; returns its index.
  size_t add(const void* data, size_t size, uint32_t target) {
    while (bytes.size() % 4) bytes.push_back('\0');
    Json v = {{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}};
    if (target) v["target"] = target;
    bytes.append(static_cast<const char*>(data), size);
    views.push_back(std::move(v));
    return views.size() - 1;
  }
};

void appendU32(std::string& out, uint32_t v) {
  char b[4];
  std::memcpy(b, &v, 4);
  out.append(b, 4);
}

// Plain accessors: one array per attribute shared by every submesh's
// primitive, exact floats.
void writePlainPrimitives(const Geometry& g, const std::vector<float>& positions, const glm::vec3& lo,
                          const glm::vec3& hi, const std::vector<Submesh>& submeshes, const MeshData& mesh, Bin& bin,
                          Json& accessors, Json& primitives) {
  const size_t n = g.positions.size();
  accessors.push_back({{"bufferView", bin.add(positions.data(), positions.size() * 4, kArrayBuffer)},
                       {"componentType", kFloat},
                       {"count", n},
                       {"type", "VEC3"},
                       {"min", {lo.x, lo.y, lo.z}},
                       {"max", {hi.x, hi.y, hi.z}}});
  Json attributes = {{"POSITION", accessors.size() - 1}};
  if (!g.normals.empty()) {
    accessors.push_back({{"bufferView", bin.add(g.normals.data(), n * 12, kArrayBuffer)},
                         {"componentType", kFloat},
                         {"count", n},
                         {"type", "VEC3"}});
    attributes["NORMAL"] = accessors.size() - 1;
  }
  if (!g.uvs.empty()) {
    accessors.push_back(
        {{"bufferView", bin.add(g.uvs.data(), n * 8, kArrayBuffer)}, {"componentType", kFloat}, {"count", n}, {"type", "VEC2"}});
    attributes["TEXCOORD_0"] = accessors.size() - 1;
  }
  const size_t indexView = bin.add(g.indices.data(), g.indices.size() * 4, kElementArrayBuffer);
  for (const Submesh& s : submeshes) {
    if (s.indexCount == 0) continue;
    accessors.push_back({{"bufferView", indexView},
                         {"byteOffset", size_t(s.firstIndex) * 4},
                         {"componentType", kUnsignedInt},
                         {"count", s.indexCount},
                         {"type", "SCALAR"}});
    Json p = {{"attributes", attributes}, {"indices", accessors.size() - 1}, {"mode", 4}};
    if (s.material >= 0 && s.material < int(mesh.materials.size())) p["material"] = s.material;
    primitives.push_back(std::move(p));
  }
}

}  // namespace

bool writeGlb(const MeshData& mesh, const Geometry& g, const std::string& path, const ExportOptions& o,
              PendingFiles& files, const Progress* progress, std::string& error, double* quantizationError) {
  Bin bin;
  Json accessors = Json::array();
  const size_t n = g.positions.size();

  std::vector<float> positions(n * 3);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 p(g.world ? g.positions[i] - g.origin : g.positions[i]);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    std::memcpy(&positions[i * 3], &p, sizeof p);
  }
  std::vector<Submesh> submeshes = mesh.submeshes;
  if (submeshes.empty()) submeshes.push_back({0, uint32_t(g.indices.size()), -1});
  Json primitives = Json::array();
  if (o.dracoBits > 0) {
    std::vector<glm::vec3> p3(n);
    std::memcpy(p3.data(), positions.data(), n * sizeof(glm::vec3));
    if (quantizationError) *quantizationError = 0.0;
    for (const Submesh& s : submeshes) {
      if (s.indexCount == 0) continue;
      DracoPrimitive d;
      if (!encodeDraco(p3, g.normals, g.uvs, g.indices.data() + s.firstIndex, s.indexCount, o.dracoBits, d, error)) {
        error = path + ": " + error;
        return false;
      }
      if (quantizationError) *quantizationError = std::max(*quantizationError, d.maxPositionError);
      const size_t view = bin.add(d.bytes.data(), d.bytes.size(), 0);
      Json attributes, dracoAttributes;
      accessors.push_back({{"componentType", kFloat}, {"count", d.points}, {"type", "VEC3"},
                           {"min", {d.lo.x, d.lo.y, d.lo.z}}, {"max", {d.hi.x, d.hi.y, d.hi.z}}});
      attributes["POSITION"] = accessors.size() - 1, dracoAttributes["POSITION"] = d.positionId;
      if (d.normalId >= 0) {
        accessors.push_back({{"componentType", kFloat}, {"count", d.points}, {"type", "VEC3"}});
        attributes["NORMAL"] = accessors.size() - 1, dracoAttributes["NORMAL"] = d.normalId;
      }
      if (d.uvId >= 0) {
        accessors.push_back({{"componentType", kFloat}, {"count", d.points}, {"type", "VEC2"}});
        attributes["TEXCOORD_0"] = accessors.size() - 1, dracoAttributes["TEXCOORD_0"] = d.uvId;
      }
      accessors.push_back({{"componentType", kUnsignedInt}, {"count", size_t(d.faces) * 3}, {"type", "SCALAR"}});
      Json p = {{"attributes", attributes},
                {"indices", accessors.size() - 1},
                {"mode", 4},
                {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", dracoAttributes}}}}}};
      if (s.material >= 0 && s.material < int(mesh.materials.size())) p["material"] = s.material;
      primitives.push_back(std::move(p));
      if (isCancelled(progress)) return false;
    }
    reportProgress(progress, 0.6, "Writing materials");
  } else {
    reportProgress(progress, 0.4, "Writing faces");
    writePlainPrimitives(g, positions, lo, hi, submeshes, mesh, bin, accessors, primitives);
  }
  if (isCancelled(progress)) return false;
  Json images = Json::array(), textures = Json::array(), materials = Json::array();
  std::vector<int> textureIndex(mesh.textures.size(), -1);
  for (const Material& m : mesh.materials) {
    Json pbr = {{"baseColorFactor", {m.baseColor.r, m.baseColor.g, m.baseColor.b, m.baseColor.a}},
                {"metallicFactor", 0.0},
                {"roughnessFactor", 1.0}};
    const int t = m.diffuseTexture;
    if (t >= 0 && t < int(mesh.textures.size()) && !g.uvs.empty()) {
      if (textureIndex[size_t(t)] < 0) {
        std::string ext;
        const std::string bytes = textureFileBytes(mesh.textures[size_t(t)], true, ext, error);
        if (bytes.empty()) {
          error = path + ": " + error;
          return false;
        }
        images.push_back({{"bufferView", bin.add(bytes.data(), bytes.size(), 0)},
                          {"mimeType", ext == ".jpg" ? "image/jpeg" : "image/png"}});
        textures.push_back({{"source", images.size() - 1}});
        textureIndex[size_t(t)] = int(textures.size()) - 1;
      }
      pbr["baseColorTexture"] = {{"index", textureIndex[size_t(t)]}};
    }
    Json mj = {{"name", m.name}, {"pbrMetallicRoughness", pbr}};
    if (m.baseColor.a < 1.0f) mj["alphaMode"] = "BLEND";
    materials.push_back(std::move(mj));
  }
  while (bin.bytes.size() % 4) bin.bytes.push_back('\0');

  Json node = {{"mesh", 0}, {"name", "mesh"}};
  if (g.world) node["translation"] = {g.origin.x, g.origin.y, g.origin.z};
  Json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "Hybridscape"}};
  if (o.dracoBits > 0) {
    j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  }
  if (!o.comment.empty()) j["asset"]["extras"] = {{"comment", o.comment}};
  j["scene"] = 0;
  j["scenes"] = Json::array({{{"nodes", {0}}}});
  j["nodes"] = Json::array({node});
  j["meshes"] = Json::array({{{"primitives", primitives}}});
  j["accessors"] = std::move(accessors);
  j["bufferViews"] = std::move(bin.views);
  j["buffers"] = Json::array({{{"byteLength", bin.bytes.size()}}});
  if (!materials.empty()) j["materials"] = std::move(materials);
  if (!textures.empty()) {
    j["textures"] = std::move(textures);
    j["images"] = std::move(images);
  }
  std::string text = writeJson(j, -1);
  while (text.size() % 4) text.push_back(' ');

  const uint64_t total = 12 + 8 + text.size() + 8 + bin.bytes.size();
  if (total > std::numeric_limits<uint32_t>::max()) {
    error = path + ": " + std::to_string(total) + " bytes exceed GLB's 4 GB limit; export as PLY or OBJ";
    return false;
  }
  std::string out;
  out.reserve(size_t(total));
  appendU32(out, 0x46546C67);  // "glTF"
  appendU32(out, 2);
  appendU32(out, uint32_t(total));
  appendU32(out, uint32_t(text.size()));
  appendU32(out, 0x4E4F534A);  // "JSON"
  out += text;
  appendU32(out, uint32_t(bin.bytes.size()));
  appendU32(out, 0x004E4942);  // "BIN\0"
  out += bin.bytes;
  return files.add(path, out, error);
}

}  // namespace hs::mesh::exporting
