#include "cli/terrain_cli.h"

#include <charconv>
#include <cmath>
#include <filesystem>

namespace hs::cli::terrain_cli {
namespace {

bool number(std::string s, double& v) {
  if (!s.empty() && s[0] == '+') s.erase(0, 1);
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}

bool integer(const std::string& s, int& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

bool openScene(const std::string& path, scene::Document& doc, std::string& error) {
  std::optional<scene::SceneState> s = scene::loadScene(path, error);
  if (!s) {
    if (!std::filesystem::exists(path)) error += " (create it with: hybridscape-cli new " + path + ")";
    return false;
  }
  doc.reset(std::move(*s), QString::fromStdString(path));
  return true;
}

bool saveScene(const scene::Document& doc, const std::string& path, std::string& error, std::string& summary) {
  scene::SaveReport r;
  if (!scene::saveScene(doc.state(), path, error, &r)) return false;
  char buf[256];
  std::snprintf(buf, sizeof buf, "saved %s: %zu terrain tiles written (%.1f KiB), %zu unchanged, %zu removed", path.c_str(),
                r.tilesWritten, double(r.tileBytesWritten) / 1024.0, r.tilesUnchanged, r.tilesRemoved);
  summary = buf;
  return true;
}

bool parseMetres(const std::string& text, double& x, double& y, std::string& error) {
  const auto sep = text.find('x');
  const bool ok = sep == std::string::npos ? number(text, x) && ((y = x), true)
                                           : number(text.substr(0, sep), x) && number(text.substr(sep + 1), y);
  if (!ok || !(x > 0.0) || !(y > 0.0) || x > 1e7 || y > 1e7) {
    error = "size '" + text + "' is not WIDTHxHEIGHT in metres (for example 2000x2000)";
    return false;
  }
  return true;
}

bool parseSamples(const std::string& text, int& x, int& y, std::string& error) {
  const auto sep = text.find('x');
  const bool ok = sep == std::string::npos ? integer(text, x) && ((y = x), true)
                                           : integer(text.substr(0, sep), x) && integer(text.substr(sep + 1), y);
  if (!ok || x < 2 || y < 2 || x > 8193 || y > 8193) {
    error = "resolution '" + text + "' is not a sample count from 2 to 8193 (N or WxH, for example 2049)";
    return false;
  }
  return true;
}

bool parsePair(const std::string& text, double& a, double& b, std::string& error) {
  const auto sep = text.find(',');
  if (sep == std::string::npos || !number(text.substr(0, sep), a) || !number(text.substr(sep + 1), b)) {
    error = "'" + text + "' is not two numbers a,b";
    return false;
  }
  return true;
}

bool intOption(const Args& args, const std::string& name, int lo, int hi, int& out, std::string& error) {
  const auto v = args.get(name);
  if (!v) return true;
  if (!integer(*v, out) || out < lo || out > hi) {
    error = "--" + name + " takes a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
    return false;
  }
  return true;
}

bool doubleOption(const Args& args, const std::string& name, double lo, double hi, double& out, std::string& error) {
  const auto v = args.get(name);
  if (!v) return true;
  if (!number(*v, out) || out < lo || out > hi) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "--%s takes a number from %g to %g", name.c_str(), lo, hi);
    error = buf;
    return false;
  }
  return true;
}

}  // namespace hs::cli::terrain_cli
