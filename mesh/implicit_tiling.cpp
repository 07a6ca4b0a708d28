#include "mesh/implicit_tiling.h"

#include <cstring>

namespace hs::mesh {
namespace fs = std::filesystem;
namespace {

// The child subtree bitstream of a subtree holds 2^(dims * subtreeLevels)
// bits; beyond 2^34 (2 GiB of bits) no file could hold it, so such a scheme
// is refused before anything is sized from it.
constexpr int kMaxSubtreeBitsLog2 = 34;
// 48 quadtree levels split the Earth's circumference into 0.14 um: deeper
// is a broken file, and coordinates stay far inside 64 bits.
constexpr int kMaxAvailableLevels = 48;

bool intField(const Json& o, const char* key, int lo, int hi, int& out) {
  if (!o.contains(key) || !o[key].is_number_integer()) return false;
  const int64_t v = o[key].get<int64_t>();
  if (v < lo || v > hi) return false;
  out = int(v);
  return true;
}

uint64_t le64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

}  // namespace

uint64_t levelOffset(int dims, int level) {
  const uint64_t n = uint64_t(1) << (dims * level);  // callers keep dims * level <= 34
  return (n - 1) / ((uint64_t(1) << dims) - 1);
}

uint64_t mortonIndex(int dims, uint64_t x, uint64_t y, uint64_t z) {
  uint64_t m = 0;
  for (int b = 0; (b + 1) * dims <= 64; ++b) {
    m |= ((x >> b) & 1u) << (b * dims);
    m |= ((y >> b) & 1u) << (b * dims + 1);
    if (dims == 3) m |= ((z >> b) & 1u) << (b * dims + 2);
  }
  return m;
}

std::string expandImplicitUri(const std::string& uri, int level, uint64_t x, uint64_t y, uint64_t z) {
  std::string out;
  for (size_t i = 0; i < uri.size();) {
    auto take = [&](const char* key, const std::string& value) {
      const size_t n = std::strlen(key);
      if (uri.compare(i, n, key) != 0) return false;
      out += value;
      i += n;
      return true;
    };
    if (take("{level}", std::to_string(level)) || take("{x}", std::to_string(x)) || take("{y}", std::to_string(y)) ||
        take("{z}", std::to_string(z)))
      continue;
    out += uri[i++];
  }
  return out;
}

bool parseImplicitTiling(const Json& tile, ImplicitScheme& out, std::string& problem) {
  problem.clear();
  const Json* it = nullptr;
  bool extension = false;  // 3DTILES_implicit_tiling (before 1.1): maximumLevel instead of availableLevels
  if (tile.contains("implicitTiling")) {
    it = &tile["implicitTiling"];
  } else if (tile.contains("extensions") && tile["extensions"].is_object() &&
             tile["extensions"].contains("3DTILES_implicit_tiling")) {
    it = &tile["extensions"]["3DTILES_implicit_tiling"];
    extension = true;
  }
  if (!it) return false;
  if (!it->is_object()) {
    problem = "is not an object";
    return false;
  }
  const std::string scheme =
      it->contains("subdivisionScheme") && (*it)["subdivisionScheme"].is_string() ? (*it)["subdivisionScheme"].get<std::string>() : "";
  if (scheme == "QUADTREE") out.dims = 2;
  else if (scheme == "OCTREE") out.dims = 3;
  else {
    problem = "subdivisionScheme \"" + scheme + "\" is neither QUADTREE nor OCTREE";
    return false;
  }
  if (!intField(*it, "subtreeLevels", 1, kMaxSubtreeBitsLog2 / out.dims, out.subtreeLevels)) {
    problem = "subtreeLevels is not a whole number from 1 to " + std::to_string(kMaxSubtreeBitsLog2 / out.dims);
    return false;
  }
  int maximumLevel = 0;
  if (!extension && !intField(*it, "availableLevels", 1, kMaxAvailableLevels, out.availableLevels)) {
    problem = "availableLevels is not a whole number from 1 to " + std::to_string(kMaxAvailableLevels);
    return false;
  }
  if (extension) {
    if (!intField(*it, "maximumLevel", 0, kMaxAvailableLevels - 1, maximumLevel)) {
      problem = "maximumLevel is not a whole number from 0 to " + std::to_string(kMaxAvailableLevels - 1);
      return false;
    }
    out.availableLevels = maximumLevel + 1;
  }
  const Json* subtrees = it->contains("subtrees") ? &(*it)["subtrees"] : nullptr;
  if (!subtrees || !subtrees->is_object() || !subtrees->contains("uri") || !(*subtrees)["uri"].is_string()) {
    problem = "subtrees.uri is missing";
    return false;
  }
  out.subtreeUri = (*subtrees)["uri"].get<std::string>();
  return true;
}

bool readSubtree(const fs::path& file, const std::vector<uint8_t>& bytes, const ImplicitScheme& scheme,
                 size_t contentCount, const ReadFile& readFile, Subtree& out, std::string& problem) {
  out = Subtree{};
  // The JSON and, in a binary subtree, the chunk that buffers without a uri name.
  std::string_view jsonText;
  const uint8_t* binary = nullptr;
  uint64_t binaryBytes = 0;
  if (bytes.size() >= 4 && std::memcmp(bytes.data(), "subt", 4) == 0) {
    if (bytes.size() < 24) {
      problem = "its binary header is truncated (" + std::to_string(bytes.size()) + " of 24 bytes)";
      return false;
    }
    const uint64_t jsonLength = le64(&bytes[8]), binLength = le64(&bytes[16]);
    if (jsonLength > bytes.size() - 24 || binLength > bytes.size() - 24 - jsonLength) {
      problem = "its header names " + std::to_string(jsonLength) + " bytes of JSON and " + std::to_string(binLength) +
                " of binary, more than the file's " + std::to_string(bytes.size()) + " bytes (truncated?)";
      return false;
    }
    jsonText = std::string_view(reinterpret_cast<const char*>(&bytes[24]), size_t(jsonLength));
    binary = bytes.data() + 24 + jsonLength;
    binaryBytes = binLength;
  } else {
    jsonText = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  // Padding spaces and NULs after the JSON are allowed.
  while (!jsonText.empty() && (jsonText.back() == ' ' || jsonText.back() == '\0')) jsonText.remove_suffix(1);
  std::string perr;
  const std::optional<Json> doc = parseJson(jsonText, perr);
  if (!doc || !doc->is_object()) {
    problem = doc ? "its JSON is not an object" : "its JSON does not parse (" + perr + ")";
    return false;
  }
  const Json& j = *doc;

  // Buffers: the binary chunk or an external file, each checked for its declared length.
  std::vector<std::vector<uint8_t>> external;
  struct Span { const uint8_t* data; uint64_t size; };
  std::vector<Span> buffers;
  if (j.contains("buffers")) {
    if (!j["buffers"].is_array()) {
      problem = "buffers is not an array";
      return false;
    }
    external.reserve(j["buffers"].size());
    for (size_t i = 0; i < j["buffers"].size(); ++i) {
      const Json& b = j["buffers"][i];
      const std::string at = "buffers[" + std::to_string(i) + "]";
      if (!b.is_object() || !b.contains("byteLength") || !b["byteLength"].is_number_unsigned()) {
        problem = at + ".byteLength is missing";
        return false;
      }
      const uint64_t length = b["byteLength"].get<uint64_t>();
      if (b.contains("uri")) {
        if (!b["uri"].is_string()) {
          problem = at + ".uri is not a string";
          return false;
        }
        external.emplace_back();
        std::string why;
        const fs::path path = file.parent_path() / b["uri"].get<std::string>();
        if (!readFile(path, external.back(), why)) {
          problem = at + " (" + path.string() + ") " + why;
          return false;
        }
        if (external.back().size() < length) {
          problem = at + " (" + path.string() + ") has " + std::to_string(external.back().size()) +
                    " bytes, fewer than its byteLength " + std::to_string(length);
          return false;
        }
        buffers.push_back({external.back().data(), length});
      } else {
        if (!binary || length > binaryBytes) {
          problem = at + " names the binary chunk, which " +
                    (binary ? "holds only " + std::to_string(binaryBytes) + " bytes" : std::string("this JSON subtree has not"));
          return false;
        }
        buffers.push_back({binary, length});
      }
    }
  }

  // One availability object; `bits` is how many indices it must cover.
  auto availability = [&](const Json& a, const std::string& name, uint64_t bits, Availability& into) {
    if (!a.is_object()) {
      problem = name + " is not an object";
      return false;
    }
    if (a.contains("constant")) {
      if (!a["constant"].is_number_integer() || (a["constant"].get<int64_t>() != 0 && a["constant"].get<int64_t>() != 1)) {
        problem = name + ".constant is neither 0 nor 1";
        return false;
      }
      into.constant = true;
      into.value = a["constant"].get<int64_t>() == 1;
      return true;
    }
    const char* key = a.contains("bitstream") ? "bitstream" : "bufferView";  // bufferView: the 1.0 extension
    if (!a.contains(key) || !a[key].is_number_unsigned()) {
      problem = name + " has neither a constant nor a bitstream";
      return false;
    }
    const uint64_t view = a[key].get<uint64_t>();
    if (!j.contains("bufferViews") || !j["bufferViews"].is_array() || view >= j["bufferViews"].size()) {
      problem = name + " names bufferView " + std::to_string(view) + ", which is not there";
      return false;
    }
    const Json& v = j["bufferViews"][size_t(view)];
    const std::string at = "bufferViews[" + std::to_string(view) + "]";
    if (!v.is_object() || !v.contains("buffer") || !v["buffer"].is_number_unsigned() || !v.contains("byteLength") ||
        !v["byteLength"].is_number_unsigned() || (v.contains("byteOffset") && !v["byteOffset"].is_number_unsigned())) {
      problem = at + " lacks buffer or byteLength, or has a negative number";
      return false;
    }
    const uint64_t buffer = v["buffer"].get<uint64_t>(), length = v["byteLength"].get<uint64_t>(),
                   offset = v.contains("byteOffset") ? v["byteOffset"].get<uint64_t>() : 0;
    if (buffer >= buffers.size()) {
      problem = at + " names buffer " + std::to_string(buffer) + ", which is not there";
      return false;
    }
    if (offset > buffers[size_t(buffer)].size || length > buffers[size_t(buffer)].size - offset) {
      problem = at + " (" + std::to_string(offset) + " + " + std::to_string(length) + " bytes) runs past its buffer of " +
                std::to_string(buffers[size_t(buffer)].size) + " bytes";
      return false;
    }
    const uint64_t need = (bits + 7) / 8;
    if (length < need) {
      problem = name + " has " + std::to_string(length) + " bytes, fewer than the " + std::to_string(need) +
                " its " + std::to_string(bits) + " bits need";
      return false;
    }
    into.constant = false;
    const uint8_t* p = buffers[size_t(buffer)].data + offset;
    into.bits.assign(p, p + need);
    return true;
  };

  const uint64_t tileBits = levelOffset(scheme.dims, scheme.subtreeLevels);
  const uint64_t childBits = uint64_t(1) << (scheme.dims * scheme.subtreeLevels);
  if (!j.contains("tileAvailability")) {
    problem = "tileAvailability is missing";
    return false;
  }
  if (!availability(j["tileAvailability"], "tileAvailability", tileBits, out.tiles)) return false;
  if (!j.contains("childSubtreeAvailability")) {
    problem = "childSubtreeAvailability is missing";
    return false;
  }
  if (!availability(j["childSubtreeAvailability"], "childSubtreeAvailability", childBits, out.childSubtrees))
    return false;
  out.contents.assign(contentCount, Availability{});  // absent: no content anywhere
  if (j.contains("contentAvailability")) {
    const Json& c = j["contentAvailability"];
    const size_t n = c.is_array() ? c.size() : 1;
    if (n != contentCount) {
      problem = "contentAvailability has " + std::to_string(n) + " entries for the tile's " +
                std::to_string(contentCount) + " contents";
      return false;
    }
    for (size_t i = 0; i < n; ++i)
      if (!availability(c.is_array() ? c[i] : c, "contentAvailability[" + std::to_string(i) + "]", tileBits,
                        out.contents[i]))
        return false;
  }
  return true;
}

}  // namespace hs::mesh
