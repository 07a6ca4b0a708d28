#include "mesh/gltf_geometry.h"

#include <draco/compression/decode.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/json.h"
#include "mesh/tinygltf_options.h"

namespace hs::mesh {
namespace {

constexpr int kTriangles = 4, kTriangleStrip = 5, kTriangleFan = 6;

int componentBytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT: case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentsOf(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

// One component as a double: floats as they are, integers as themselves or,
// normalized, mapped to [0, 1] / [-1, 1] as glTF 2.0 says.
double component(const uint8_t* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); return v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v; std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v; std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const int8_t v = int8_t(p[0]);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    default: return 0.0;
  }
}

// Accessor `index` as `n` doubles per element, every number behind it
// checked; "" or what is wrong.
std::string readAccessor(const tinygltf::Model& m, int index, int n, std::vector<double>& out) {
  if (index < 0 || size_t(index) >= m.accessors.size()) return "accessor " + std::to_string(index) + " does not exist";
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  const std::string name = "accessor " + std::to_string(index);
  if (a.sparse.isSparse) return name + " is sparse (not read)";
  const int cb = componentBytes(a.componentType), comps = componentsOf(a.type);
  if (cb == 0 || comps != n) return name + " has a type this attribute cannot have";
  if (a.bufferView < 0 || size_t(a.bufferView) >= m.bufferViews.size()) return name + " has no buffer view";
  const tinygltf::BufferView& v = m.bufferViews[size_t(a.bufferView)];
  if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size()) return name + "'s buffer view names no buffer";
  const std::vector<unsigned char>& data = m.buffers[size_t(v.buffer)].data;
  const size_t element = size_t(cb) * size_t(n);
  const size_t stride = v.byteStride ? v.byteStride : element;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
    return name + "'s buffer view runs past its buffer";
  if (a.count == 0) return "";
  if (stride < element || a.byteOffset > v.byteLength || (a.count - 1) > (v.byteLength - a.byteOffset) / stride ||
      (a.count - 1) * stride + element > v.byteLength - a.byteOffset)
    return name + " declares " + std::to_string(a.count) + " elements; its buffer view holds fewer";
  const uint8_t* base = data.data() + v.byteOffset + a.byteOffset;
  out.resize(a.count * size_t(n));
  for (size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < n; ++c) out[i * size_t(n) + size_t(c)] = component(base + i * stride + size_t(c * cb), a.componentType, a.normalized);
  return "";
}

// A Draco-compressed primitive's triangles, positions and UVs; "" or what
// is wrong.
std::string decodeDraco(const tinygltf::Model& m, const tinygltf::Value& ext, std::vector<double>& positions,
                        std::vector<double>& uvs, std::vector<uint32_t>& indices) {
  const tinygltf::Value& view = ext.Get("bufferView");
  const tinygltf::Value& attrs = ext.Get("attributes");
  if (!view.IsInt() || !attrs.IsObject()) return "its KHR_draco_mesh_compression lacks bufferView or attributes";
  const int vi = view.Get<int>();
  if (vi < 0 || size_t(vi) >= m.bufferViews.size()) return "its Draco buffer view does not exist";
  const tinygltf::BufferView& v = m.bufferViews[size_t(vi)];
  if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size()) return "its Draco buffer view names no buffer";
  const std::vector<unsigned char>& data = m.buffers[size_t(v.buffer)].data;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
    return "its Draco buffer view runs past its buffer";
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data.data() + v.byteOffset), v.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return "its Draco data does not decode (" + decoded.status().error_msg_string() + ")";
  const draco::Mesh& mesh = *decoded.value();
  auto attribute = [&](const char* name, int n, std::vector<double>& out) -> std::string {
    const tinygltf::Value& id = attrs.Get(name);
    if (!id.IsInt()) return "";
    const draco::PointAttribute* a = mesh.GetAttributeByUniqueId(uint32_t(id.Get<int>()));
    if (!a || a->num_components() != n) return std::string("its Draco ") + name + " attribute is missing or of another size";
    out.resize(size_t(mesh.num_points()) * size_t(n));
    float value[4];
    for (uint32_t p = 0; p < mesh.num_points(); ++p) {
      if (!a->ConvertValue<float>(a->mapped_index(draco::PointIndex(p)), uint8_t(n), value))
        return std::string("its Draco ") + name + " attribute does not convert";
      for (int c = 0; c < n; ++c) out[size_t(p) * size_t(n) + size_t(c)] = value[c];
    }
    return "";
  };
  if (std::string e = attribute("POSITION", 3, positions); !e.empty()) return e;
  if (positions.empty()) return "its Draco data has no POSITION";
  if (std::string e = attribute("TEXCOORD_0", 2, uvs); !e.empty()) uvs.clear();
  indices.reserve(size_t(mesh.num_faces()) * 3);
  for (uint32_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& face = mesh.face(draco::FaceIndex(f));
    for (int c = 0; c < 3; ++c) indices.push_back(face[c].value());
  }
  return "";
}

// Triangle lists from a primitive's index list (or 0..n-1 without one).
std::vector<uint32_t> triangleList(int mode, const std::vector<uint32_t>& idx) {
  if (mode == kTriangles) return std::vector<uint32_t>(idx.begin(), idx.begin() + long(idx.size() / 3 * 3));
  std::vector<uint32_t> out;
  for (size_t i = 2; i < idx.size(); ++i) {
    if (mode == kTriangleStrip) {
      if (i % 2 == 0) out.insert(out.end(), {idx[i - 2], idx[i - 1], idx[i]});
      else out.insert(out.end(), {idx[i - 1], idx[i - 2], idx[i]});
    } else {
      out.insert(out.end(), {idx[0], idx[i - 1], idx[i]});
    }
  }
  return out;
}

glm::dmat4 nodeMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());  // column-major, as glTF
  glm::dmat4 t(1.0);
  if (n.translation.size() == 3) t = glm::translate(t, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4)
    t *= glm::mat4_cast(glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])));
  if (n.scale.size() == 3) t = glm::scale(t, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return t;
}

struct Walker {
  const tinygltf::Model& m;
  const std::string& what;
  GltfGeometry& out;
  bool allUvs = true;
  std::vector<glm::vec2> uvs;

  void primitive(const tinygltf::Primitive& p, const glm::dmat4& world, const std::string& where) {
    if (p.mode != kTriangles && p.mode != kTriangleStrip && p.mode != kTriangleFan) {
      out.warnings.push_back(what + ": " + where + " draws points or lines (mode " + std::to_string(p.mode) +
                             "): skipped");
      return;
    }
    std::vector<double> pos, uv;
    std::vector<uint32_t> idx;
    std::string problem;
    if (auto draco = p.extensions.find("KHR_draco_mesh_compression"); draco != p.extensions.end()) {
      problem = decodeDraco(m, draco->second, pos, uv, idx);
    } else {
      auto at = p.attributes.find("POSITION");
      if (at == p.attributes.end()) problem = "it has no POSITION";
      else problem = readAccessor(m, at->second, 3, pos);
      if (problem.empty())
        if (auto t = p.attributes.find("TEXCOORD_0"); t == p.attributes.end() || !readAccessor(m, t->second, 2, uv).empty())
          uv.clear();
      if (problem.empty() && p.indices >= 0) {
        std::vector<double> raw;
        problem = readAccessor(m, p.indices, 1, raw);
        if (problem.empty() && m.accessors[size_t(p.indices)].componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            m.accessors[size_t(p.indices)].componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            m.accessors[size_t(p.indices)].componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
          problem = "its indices are not unsigned integers";
        // Only unsigned integer indices are converted: a float accessor's
        // NaN or 1e30 has no uint32_t (found by fuzz_tileset_content).
        if (problem.empty()) {
          idx.reserve(raw.size());
          for (double d : raw) idx.push_back(uint32_t(d));
        }
      } else if (problem.empty()) {
        for (uint32_t i = 0; i < pos.size() / 3; ++i) idx.push_back(i);
      }
    }
    if (!problem.empty()) {
      out.warnings.push_back(what + ": " + where + ": " + problem + "; skipped");
      return;
    }
    const size_t count = pos.size() / 3;
    std::vector<uint32_t> tris = triangleList(p.mode, idx);
    out.declaredTriangles += tris.size() / 3;
    const uint32_t first = uint32_t(out.positions.size());
    size_t badIndex = 0, badPosition = 0;
    std::vector<uint8_t> finite(count, 1);
    for (size_t i = 0; i < count; ++i) {
      const glm::dvec4 w = world * glm::dvec4(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2], 1.0);
      out.positions.emplace_back(w);
      if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z)) finite[i] = 0;
    }
    const bool hasUv = uv.size() == count * 2;
    allUvs = allUvs && hasUv;
    for (size_t i = 0; i < count; ++i)
      uvs.emplace_back(hasUv ? glm::vec2(float(uv[i * 2]), float(uv[i * 2 + 1])) : glm::vec2(0.0f));
    for (size_t t = 0; t + 2 < tris.size(); t += 3) {
      const uint32_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
      if (a >= count || b >= count || c >= count) { ++badIndex; continue; }
      if (!finite[a] || !finite[b] || !finite[c]) { ++badPosition; continue; }
      if (a == b || b == c || a == c) continue;
      out.indices.insert(out.indices.end(), {first + a, first + b, first + c});
    }
    if (badIndex)
      out.warnings.push_back(what + ": " + where + ": " + std::to_string(badIndex) +
                             " triangles index past its vertices; dropped");
    if (badPosition)
      out.warnings.push_back(what + ": " + where + ": " + std::to_string(badPosition) +
                             " triangles have a non-finite position; dropped");
  }

  void node(int index, const glm::dmat4& parent, int depth) {
    if (index < 0 || size_t(index) >= m.nodes.size() || depth > 64) {
      out.warnings.push_back(what + ": node " + std::to_string(index) + " does not exist (or nodes form a cycle)");
      return;
    }
    const tinygltf::Node& n = m.nodes[size_t(index)];
    const glm::dmat4 world = parent * nodeMatrix(n);
    if (n.mesh >= 0) {
      if (size_t(n.mesh) >= m.meshes.size()) {
        out.warnings.push_back(what + ": node " + std::to_string(index) + " names mesh " + std::to_string(n.mesh) +
                               ", which does not exist");
      } else {
        const tinygltf::Mesh& mesh = m.meshes[size_t(n.mesh)];
        for (size_t p = 0; p < mesh.primitives.size(); ++p)
          primitive(mesh.primitives[p], world,
                    "mesh " + std::to_string(n.mesh) + " primitive " + std::to_string(p));
      }
    }
    for (int c : n.children) node(c, world, depth + 1);
  }
};

// Images are not decoded (the hierarchy takes geometry and UVs; paged
// textures are not done yet): their bytes are left as they are.
// tinygltf (Debian's 2.5) refuses a primitive whose indices accessor has
// no bufferView unless its own Draco decoder is compiled in, and a Draco
// primitive's indices accessor has none (the indices are in the Draco
// data). decodeDraco reads the faces from the Draco data and never that
// accessor, so Draco primitives lose their "indices" before tinygltf sees
// them. Returns the rewritten bytes, or nothing when no change is needed
// (or the JSON does not parse: tinygltf then says why).
std::optional<std::vector<uint8_t>> withoutDracoIndices(const std::vector<uint8_t>& bytes, bool binary) {
  size_t jsonAt = 0, jsonSize = bytes.size();
  if (binary) {
    if (bytes.size() < 20) return std::nullopt;
    uint32_t chunk = 0;
    std::memcpy(&chunk, bytes.data() + 12, 4);
    if (std::memcmp(bytes.data() + 16, "JSON", 4) != 0 || chunk > bytes.size() - 20) return std::nullopt;
    jsonAt = 20, jsonSize = chunk;
  }
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()) + jsonAt, jsonSize);
  if (text.find("KHR_draco_mesh_compression") == std::string_view::npos) return std::nullopt;
  Json gltf = Json::parse(text, nullptr, false);
  if (gltf.is_discarded() || !gltf.is_object() || !gltf.contains("meshes") || !gltf["meshes"].is_array())
    return std::nullopt;
  bool changed = false;
  for (Json& mesh : gltf["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (Json& p : mesh["primitives"])
      if (p.is_object() && p.contains("indices") && p.contains("extensions") && p["extensions"].is_object() &&
          p["extensions"].contains("KHR_draco_mesh_compression")) {
        p.erase("indices");
        changed = true;
      }
  }
  if (!changed) return std::nullopt;
  std::string json = gltf.dump();
  if (!binary) return std::vector<uint8_t>(json.begin(), json.end());
  while (json.size() % 4) json.push_back(' ');
  const size_t rest = bytes.size() - 20 - jsonSize;
  std::vector<uint8_t> out(20 + json.size() + rest);
  std::memcpy(out.data(), bytes.data(), 12);
  const uint32_t total = uint32_t(out.size()), chunk = uint32_t(json.size());
  std::memcpy(out.data() + 8, &total, 4);
  std::memcpy(out.data() + 12, &chunk, 4);
  std::memcpy(out.data() + 16, "JSON", 4);
  std::memcpy(out.data() + 20, json.data(), json.size());
  if (rest) std::memcpy(out.data() + 20 + json.size(), bytes.data() + 20 + jsonSize, rest);
  return out;
}

// The chunks of a GLB checked before tinygltf sees them: tinygltf 2.8
// compares the BIN chunk's length with the bytes after the JSON chunk
// without its own 8-byte header, so a BIN chunk up to 8 bytes too long was
// copied from past the end (found by fuzz_tileset_content). "" when sound.
std::string glbChunkProblem(const std::vector<uint8_t>& b) {
  if (b.size() < 20) return "its GLB header is truncated";
  uint32_t jsonLength = 0;
  std::memcpy(&jsonLength, b.data() + 12, 4);
  const uint64_t binAt = 20 + uint64_t(jsonLength);
  if (binAt > b.size()) return "its JSON chunk runs past the file";
  if (binAt == b.size()) return "";
  if (binAt + 8 > b.size()) return "its BIN chunk header is truncated";
  uint32_t binLength = 0;
  std::memcpy(&binLength, b.data() + binAt, 4);
  if (binAt + 8 + binLength > b.size())
    return "its BIN chunk (" + std::to_string(binLength) + " bytes) runs past the file's " + std::to_string(b.size());
  return "";
}

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

}  // namespace

bool readGltfGeometry(const std::vector<uint8_t>& bytes, const std::string& baseDir, const std::string& what,
                      GltfGeometry& out, std::string& error) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  if (bytes.size() > 0x7fffffffu) {
    error = what + ": larger than 2 GB (glTF's limit)";
    return false;
  }
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const std::optional<std::vector<uint8_t>> rewritten = withoutDracoIndices(bytes, binary);
  const std::vector<uint8_t>& in = rewritten ? *rewritten : bytes;
  if (binary) {
    if (const std::string problem = glbChunkProblem(in); !problem.empty()) {
      error = what + ": not a readable glTF asset (" + problem + ")";
      return false;
    }
  }
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, in.data(), unsigned(in.size()), baseDir)
                         : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(in.data()),
                                                      unsigned(in.size()), baseDir);
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    error = what + ": not a readable glTF asset (" + (err.empty() ? std::string("tinygltf gave no reason") : err) + ")";
    return false;
  }
  Walker w{model, what, out, true, {}};
  // y up as glTF has it; the caller turns the frame.
  const glm::dmat4 identity(1.0);
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? model.defaultScene : 0;
    for (int n : model.scenes[size_t(s)].nodes) w.node(n, identity, 0);
  } else {
    // No scene: every node no other node names as a child.
    std::vector<uint8_t> child(model.nodes.size(), 0);
    for (const auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = 1;
    for (size_t n = 0; n < model.nodes.size(); ++n)
      if (!child[n]) w.node(int(n), identity, 0);
  }
  if (w.allUvs && !w.uvs.empty()) out.uvs = std::move(w.uvs);
  if (auto rtc = model.extensions.find("CESIUM_RTC"); rtc != model.extensions.end()) {
    const tinygltf::Value& c = rtc->second.Get("center");
    if (c.IsArray() && c.ArrayLen() == 3 && c.Get(0).IsNumber() && c.Get(1).IsNumber() && c.Get(2).IsNumber())
      out.rtcCenter = glm::dvec3(c.Get(0).GetNumberAsDouble(), c.Get(1).GetNumberAsDouble(), c.Get(2).GetNumberAsDouble());
    else
      out.warnings.push_back(what + ": its CESIUM_RTC centre is not three numbers; ignored");
  }
  return true;
}

}  // namespace hs::mesh
