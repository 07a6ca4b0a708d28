#pragma once
// Reading the .hscene description's JSON: each helper names the JSON path
// of what it could not read ("assets[0].lods[1].hausdorff_m: expected a
// finite number"), and the first failure is the one reported. The scene's
// and the terrains' readers (scene_json.cpp, terrain_json.cpp) build on it.
#include <cmath>
#include <string>

#include <QJsonArray>
#include <QJsonValue>

namespace hs::scene {

struct JsonPathReader {
  std::string& error;

  bool fail(const std::string& path, const std::string& what) {
    if (error.empty()) error = path + ": " + what;
    return false;
  }
  bool number(const QJsonValue& v, const std::string& path, double& out) {
    if (!v.isDouble() || !std::isfinite(v.toDouble())) return fail(path, "expected a finite number");
    out = v.toDouble();
    return true;
  }
  // An array of exactly `n` finite numbers; `shape` names it in the message
  // ("[x, y, z]"), else "n numbers".
  bool numbers(const QJsonValue& v, const std::string& path, double* out, int n, const char* shape = nullptr) {
    const QJsonArray a = v.toArray();
    if (!v.isArray() || a.size() != n)
      return fail(path, std::string("expected ") + (shape ? shape : std::to_string(n) + " numbers"));
    for (int i = 0; i < n; ++i)
      if (!number(a[i], path + "[" + std::to_string(i) + "]", out[i])) return false;
    return true;
  }
};

}  // namespace hs::scene
