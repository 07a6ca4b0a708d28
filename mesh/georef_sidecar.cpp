#include "mesh/georef_sidecar.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

#include "mesh/byte_source.h"

namespace hs::mesh {
namespace {

namespace fs = std::filesystem;

// Up to `want` numbers separated by spaces, tabs or commas; false if the
// line holds anything else or fewer than `need`.
bool readNumbers(std::string_view line, double* out, int need, int want, int& got) {
  got = 0;
  const char* p = line.data();
  const char* end = p + line.size();
  while (p < end) {
    while (p < end && (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r')) ++p;
    if (p >= end) break;
    if (got == want) return false;
    if (*p == '+') ++p;
    double v = 0;
    const auto r = std::from_chars(p, end, v);
    if (r.ec != std::errc() || !std::isfinite(v)) return false;
    out[got++] = v;
    p = r.ptr;
  }
  return got >= need;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

}  // namespace

bool readGeoOffsetFile(const std::string& path, GeoOffset& out, std::string& error) {
  std::string text;
  if (!readWholeFile(path, text, error)) return false;
  if (text.find('\0') != std::string::npos) {
    error = path + ": not a text offset file (binary data)";
    return false;
  }
  const std::string name = lower(fs::path(path).filename().string());
  const bool odm = name.find("odm_georeferencing_model_geo") != std::string::npos;
  int lineNo = 0;
  std::string firstText;
  for (size_t at = 0; at < text.size();) {
    const size_t nl = text.find('\n', at);
    const bool terminated = nl != std::string::npos;
    std::string_view v(text.data() + at, (terminated ? nl : text.size()) - at);
    at = terminated ? nl + 1 : text.size();
    ++lineNo;
    while (!v.empty() && (v.front() == ' ' || v.front() == '\t')) v.remove_prefix(1);
    while (!v.empty() && (v.back() == '\r' || v.back() == ' ' || v.back() == '\t')) v.remove_suffix(1);
    if (v.empty() || v.front() == '#') continue;
    double n[3] = {0, 0, 0};
    int got = 0;
    if (readNumbers(v, n, 2, 3, got)) {
      if (!odm && got < 3) {
        error = path + ":" + std::to_string(lineNo) + ": expected three numbers \"x y z\", found two";
        return false;
      }
      out.offset = glm::dvec3(n[0], n[1], got == 3 ? n[2] : 0.0);
      out.kind = odm ? "odm" : name.size() > 11 && name.ends_with("_offset.xyz") ? "pix4d" : "xyz";
      out.source = path;
      out.crs = odm ? firstText : std::string();
      // A number cut short still reads (`300.125` cut to `30`), and the
      // mesh would land hundreds of metres off without a word.
      out.warning = terminated ? std::string()
                               : path + ":" + std::to_string(lineNo) +
                                     ": the offset line has no line end, so the file may have been cut short; the "
                                     "offset was read as it stands ('" + std::string(v.substr(0, 60)) + "')";
      return true;
    }
    // ODM names its coordinate system on the line before the offset.
    if (odm && firstText.empty()) {
      firstText = std::string(v);
      continue;
    }
    error = path + ":" + std::to_string(lineNo) + ": cannot read an offset from '" +
            std::string(v.substr(0, 60)) + "' (expected \"x y z\")";
    return false;
  }
  error = path + ": holds no offset (expected a line \"x y z\"" + (odm ? " or \"easting northing\")" : ")");
  return false;
}

std::optional<GeoOffset> findGeoOffsetSidecar(const std::string& meshPath, std::vector<std::string>* tried) {
  const fs::path mesh(meshPath);
  const fs::path dir = mesh.has_parent_path() ? mesh.parent_path() : fs::path(".");
  const std::string stem = mesh.stem().string();
  std::vector<fs::path> candidates = {dir / (stem + "_offset.xyz")};
  std::error_code ec;
  std::vector<fs::path> pix4d;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file(ec) && lower(e.path().filename().string()).ends_with("_offset.xyz")) pix4d.push_back(e.path());
  if (pix4d.size() == 1) candidates.push_back(pix4d.front());
  candidates.push_back(dir / "odm_georeferencing_model_geo.txt");
  candidates.push_back(dir / ".." / "odm_georeferencing" / "odm_georeferencing_model_geo.txt");
  for (const char* n : {".offset", "_offset.txt"}) candidates.push_back(dir / (stem + n));
  candidates.push_back(dir / "offset.xyz");
  candidates.push_back(dir / "offset.txt");
  for (const fs::path& c : candidates) {
    if (!fs::is_regular_file(c, ec)) continue;
    GeoOffset g;
    std::string error;
    if (readGeoOffsetFile(c.string(), g, error)) {
      if (tried) tried->push_back(c.string() + ": used");
      return g;
    }
    if (tried) tried->push_back(error);
  }
  return std::nullopt;
}

bool parseGeoOffset(const std::string& text, GeoOffset& out, bool& isAuto, bool& isNone, std::string& error) {
  isAuto = isNone = false;
  const std::string t = lower(text);
  if (t == "auto") return isAuto = true;
  if (t == "none" || t == "0") return isNone = true;
  double n[3];
  int got = 0;
  if (!readNumbers(text, n, 3, 3, got)) {
    error = "cannot read origin '" + text + "' (use auto, none or x,y,z in metres)";
    return false;
  }
  out.offset = glm::dvec3(n[0], n[1], n[2]);
  out.kind = "manual";
  out.source = "set by hand";
  return true;
}

}  // namespace hs::mesh
