// glTF 2 checked before Assimp reads it (mesh/declared_counts.h): every
// length the file states is compared with the bytes behind it, so a chunk
// length of 0xfffffff0 or an accessor count of 10^9 is refused here rather
// than allocated by Assimp.
#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>

#include "core/json.h"
#include "mesh/declared_counts.h"

namespace hs::mesh {
namespace {

uint32_t le32(const char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

// A non-negative integer member, or `fallback` when absent; false when it
// is there but not one.
bool whole(const Json& o, const char* key, uint64_t& out, uint64_t fallback = 0) {
  out = fallback;
  if (!o.is_object() || !o.contains(key)) return true;
  const Json& v = o[key];
  if (v.is_number_unsigned()) return out = v.get<uint64_t>(), true;
  if (v.is_number_integer() && v.get<int64_t>() >= 0) return out = uint64_t(v.get<int64_t>()), true;
  return false;
}

int componentSize(uint64_t type) {
  switch (type) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
  }
}

int componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

class Checker {
 public:
  Checker(const std::string& path, std::string& error) : path_(path), error_(error) {}

  bool fail(const std::string& where, const std::string& what) {
    error_ = path_ + ": " + where + ": " + what;
    return false;
  }

  bool run(const Json& doc, const std::string& baseDir, std::optional<uint64_t> binChunk, DeclaredCounts& declared) {
    if (!doc.is_object()) return fail("the JSON", "not an object; not a glTF file");
    const Json empty = Json::array();
    const Json& buffers = doc.contains("buffers") ? doc["buffers"] : empty;
    const Json& views = doc.contains("bufferViews") ? doc["bufferViews"] : empty;
    const Json& accessors = doc.contains("accessors") ? doc["accessors"] : empty;
    const Json& meshes = doc.contains("meshes") ? doc["meshes"] : empty;
    const Json& nodes = doc.contains("nodes") ? doc["nodes"] : empty;
    for (const Json* a : {&buffers, &views, &accessors, &meshes, &nodes})
      if (!a->is_array()) return fail("the JSON", "buffers, bufferViews, accessors, meshes and nodes must be arrays");

    std::vector<uint64_t> bufferBytes;
    for (size_t i = 0; i < buffers.size(); ++i) {
      const std::string where = "buffers[" + std::to_string(i) + "]";
      uint64_t length = 0;
      if (!whole(buffers[i], "byteLength", length)) return fail(where, "byteLength is not a whole number");
      const Json* uri = buffers[i].is_object() && buffers[i].contains("uri") ? &buffers[i]["uri"] : nullptr;
      if (!uri) {
        // The GLB's own BIN chunk.
        if (i == 0 && binChunk && length > *binChunk)
          return fail(where, "declares " + std::to_string(length) + " bytes but the BIN chunk holds " +
                                 std::to_string(*binChunk) + "; the file is cut short or damaged");
      } else if (uri->is_string() && uri->get<std::string>().rfind("data:", 0) != 0) {
        std::filesystem::path file(uri->get<std::string>());
        if (file.is_relative()) file = std::filesystem::path(baseDir) / file;
        struct stat st {};
        if (::stat(file.c_str(), &st) != 0)
          return fail(where, "its file '" + uri->get<std::string>() + "' cannot be opened: " + std::strerror(errno));
        if (!S_ISREG(st.st_mode))
          return fail(where, "'" + uri->get<std::string>() + "' is " +
                                 (S_ISDIR(st.st_mode) ? "a directory" : "not a regular file (a device or a pipe)") +
                                 ", not a buffer file");
        if (uint64_t(st.st_size) < length)
          return fail(where, "declares " + std::to_string(length) + " bytes but '" + uri->get<std::string>() +
                                 "' has " + std::to_string(st.st_size) + "; it is cut short");
      }
      bufferBytes.push_back(length);
    }
    std::vector<uint64_t> viewBytes, viewStride;
    for (size_t i = 0; i < views.size(); ++i) {
      const std::string where = "bufferViews[" + std::to_string(i) + "]";
      uint64_t buffer = 0, offset = 0, length = 0, stride = 0;
      if (!whole(views[i], "buffer", buffer) || !whole(views[i], "byteOffset", offset) ||
          !whole(views[i], "byteLength", length) || !whole(views[i], "byteStride", stride))
        return fail(where, "buffer, byteOffset, byteLength and byteStride must be whole numbers");
      if (buffer >= bufferBytes.size()) return fail(where, "names buffer " + std::to_string(buffer) + ", which is not there");
      if (offset > bufferBytes[buffer] || length > bufferBytes[buffer] - offset)
        return fail(where, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                               " lie past the end of buffer " + std::to_string(buffer) + " (" +
                               std::to_string(bufferBytes[buffer]) + " bytes)");
      viewBytes.push_back(length);
      viewStride.push_back(stride);
    }
    std::vector<uint64_t> accessorCount;
    for (size_t i = 0; i < accessors.size(); ++i) {
      const std::string where = "accessors[" + std::to_string(i) + "]";
      const Json& a = accessors[i];
      uint64_t count = 0, view = 0, offset = 0, type = 0;
      if (!whole(a, "count", count) || !whole(a, "byteOffset", offset) || !whole(a, "componentType", type))
        return fail(where, "count, byteOffset and componentType must be whole numbers");
      accessorCount.push_back(count);
      if (!a.is_object() || !a.contains("bufferView")) continue;  // all zeros (or sparse): nothing to check
      if (!whole(a, "bufferView", view) || view >= viewBytes.size())
        return fail(where, "names a buffer view that is not there");
      const int elementSize =
          componentSize(type) * componentCount(a.contains("type") && a["type"].is_string() ? a["type"].get<std::string>() : "");
      if (elementSize == 0) return fail(where, "unknown componentType or type");
      if (count == 0) continue;
      const uint64_t step = viewStride[view] ? viewStride[view] : uint64_t(elementSize);
      // (count - 1) * step + elementSize + offset <= view bytes, without overflow.
      const uint64_t room = viewBytes[view];
      if (offset > room || uint64_t(elementSize) > room - offset || count - 1 > (room - offset - elementSize) / step)
        return fail(where, "declares " + std::to_string(count) + " elements of " + std::to_string(elementSize) +
                               " bytes but buffer view " + std::to_string(view) + " holds " + std::to_string(room) +
                               " bytes; the counts do not match the data");
    }

    // Triangles the scene draws: every primitive of every mesh a node of
    // the default scene (or, without scenes, any node) shows.
    std::vector<size_t> roots;
    uint64_t sceneIndex = 0;
    if (doc.contains("scenes") && doc["scenes"].is_array() && !doc["scenes"].empty()) {
      whole(doc, "scene", sceneIndex);
      if (sceneIndex < doc["scenes"].size() && doc["scenes"][sceneIndex].is_object() &&
          doc["scenes"][sceneIndex].contains("nodes") && doc["scenes"][sceneIndex]["nodes"].is_array())
        for (const Json& n : doc["scenes"][sceneIndex]["nodes"])
          if (n.is_number_unsigned()) roots.push_back(n.get<size_t>());
    } else {
      for (size_t i = 0; i < nodes.size(); ++i) roots.push_back(i);
    }
    uint64_t triangles = 0;
    size_t primitives = 0;
    std::set<size_t> seen;  // a node reached twice (a cycle, or a shared child) counts once, as Assimp reads it
    std::vector<size_t> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
      const size_t n = stack.back();
      stack.pop_back();
      if (n >= nodes.size() || !seen.insert(n).second || !nodes[n].is_object()) continue;
      const Json& node = nodes[n];
      uint64_t mesh = 0;
      if (node.contains("mesh") && whole(node, "mesh", mesh) && mesh < meshes.size() && meshes[mesh].is_object() &&
          meshes[mesh].contains("primitives") && meshes[mesh]["primitives"].is_array())
        for (const Json& p : meshes[mesh]["primitives"]) {
          uint64_t mode = 4, indices = 0, position = 0;
          whole(p, "mode", mode, 4);
          uint64_t count = 0;
          if (p.is_object() && p.contains("indices") && whole(p, "indices", indices) && indices < accessorCount.size())
            count = accessorCount[indices];
          else if (p.is_object() && p.contains("attributes") && whole(p["attributes"], "POSITION", position) &&
                   position < accessorCount.size())
            count = accessorCount[position];
          ++primitives;
          if (mode == 4) triangles += count / 3;
          else if (mode == 5 || mode == 6) triangles += count >= 3 ? count - 2 : 0;
        }
      if (node.contains("children") && node["children"].is_array())
        for (const Json& c : node["children"])
          if (c.is_number_unsigned()) stack.push_back(c.get<size_t>());
    }
    declared.triangles = size_t(triangles);
    declared.by = "glTF accessors of " + std::to_string(primitives) + " primitives";
    return true;
  }

 private:
  const std::string& path_;
  std::string& error_;
};

}  // namespace

bool checkGltf(const ByteSource& source, bool binary, const std::string& baseDir, DeclaredCounts& declared,
               std::string& error) {
  const std::string& path = source.name();
  declared = {};
  std::string buffer, jsonText;
  std::optional<uint64_t> binChunk;
  if (binary) {
    std::string_view head;
    if (!source.read(0, 20, buffer, head, error)) return false;
    if (head.size() < 20 || head.substr(0, 4) != "glTF") {
      error = path + ": not a binary glTF file (no 'glTF' header, or shorter than its 20-byte header)";
      return false;
    }
    const uint32_t version = le32(head.data() + 4), length = le32(head.data() + 8);
    const uint32_t jsonLength = le32(head.data() + 12);
    if (version != 2) return true;  // glTF 1: Assimp's own reader judges it
    if (length > source.size()) {
      error = path + ": the GLB header (byte 8) declares " + std::to_string(length) + " bytes but the file has " +
              std::to_string(source.size()) + "; it is cut short";
      return false;
    }
    if (head.substr(16, 4) != "JSON" || jsonLength > source.size() - 20) {
      error = path + ": the GLB's first chunk (byte 12) declares " + std::to_string(jsonLength) +
              " bytes of JSON but only " + std::to_string(source.size() - 20) + " follow" +
              (head.substr(16, 4) != "JSON" ? " (and it is not a JSON chunk)" : "") + "; the file is damaged";
      return false;
    }
    std::string_view text;
    if (!source.read(20, jsonLength, buffer, text, error)) return false;
    jsonText = std::string(text);
    const uint64_t binAt = 20 + ((uint64_t(jsonLength) + 3) & ~uint64_t(3));
    if (binAt + 8 <= source.size()) {
      std::string chunkBuffer;
      std::string_view chunk;
      if (!source.read(binAt, 8, chunkBuffer, chunk, error)) return false;
      const uint64_t binLength = le32(chunk.data());
      if (binLength > source.size() - binAt - 8) {
        error = path + ": the GLB's BIN chunk (byte " + std::to_string(binAt) + ") declares " +
                std::to_string(binLength) + " bytes but only " + std::to_string(source.size() - binAt - 8) +
                " follow; the file is cut short";
        return false;
      }
      binChunk = binLength;
    } else {
      binChunk = 0;
    }
  } else {
    std::string_view text;
    if (!source.read(0, size_t(source.size()), buffer, text, error)) return false;
    jsonText = std::string(text);
  }
  std::string why;
  const std::optional<Json> doc = parseJson(jsonText, why);
  if (!doc) {
    error = path + ": the glTF JSON" + (binary ? " chunk" : "") + " is not valid JSON (" + why + ")";
    return false;
  }
  return Checker(path, error).run(*doc, baseDir, binChunk, declared);
}

}  // namespace hs::mesh
