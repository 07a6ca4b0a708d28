#include "scene/ocio_config.h"


#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "core/content_hash.h"
#include "scene/color_lut.h"
#include "scene/edit.h"
#include "scene/lut_processor.h"
#include "scene/ocio_cache.h"

namespace OCIO = OCIO_NAMESPACE;
namespace fs = std::filesystem;

namespace hs::scene {
namespace {

bool readWhole(const fs::path& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream read;
  read << in.rdbuf();
  out = std::move(read).str();
  return bool(in) || in.eof();
}

bool lutExtension(const fs::path& file, const std::vector<std::string>& extensions) {
  std::string ext = file.extension().string();
  if (ext.size() < 2) return false;
  ext = ext.substr(1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return std::find(extensions.begin(), extensions.end(), ext) != extensions.end();
}

// Reads a config and what it needs from the bundle alone (a throw from
// OpenColorIO becomes `error`).
OcioConfigSummary summarise(const OcioConfigData& config) {
  OcioConfigSummary s;
  std::string error;
  const OCIO::ConstConfigRcPtr c = ocioConfigOf(config, error);
  if (!c) {
    s.error = error;
    return s;
  }
  try {
    s.defaultDisplay = c->getDefaultDisplay();
    for (int i = 0; i < c->getNumDisplays(); ++i) {
      OcioDisplay d{c->getDisplay(i), {}, {}};
      for (int k = 0; k < c->getNumViews(d.name.c_str()); ++k) d.views.push_back(c->getView(d.name.c_str(), k));
      d.defaultView = c->getDefaultView(d.name.c_str());
      s.displays.push_back(std::move(d));
    }
    s.sourceRole = c->hasRole(OCIO::ROLE_INTERCHANGE_SCENE) ? OCIO::ROLE_INTERCHANGE_SCENE
                   : c->hasRole(OCIO::ROLE_SCENE_LINEAR)   ? OCIO::ROLE_SCENE_LINEAR
                                                           : "";
  } catch (const std::exception& e) {
    s.error = config.fileName + ": " + e.what();
  }
  return s;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out.empty() ? "none" : out;
}

}  // namespace

bool ocioBundlePathSafe(const std::string& p) {
  if (p.empty() || p.front() == '/' || p.find('\\') != std::string::npos) return false;
  for (const auto& part : fs::path(p))
    if (part == ".." || part == ".") return false;
  return true;
}

std::string ocioBlobKey(uint64_t fileHash) { return "ocio/" + toHex(fileHash); }

uint64_t ocioBundleHash(const std::vector<OcioFile>& files) {
  std::string key;
  for (const OcioFile& f : files) key += f.path + '\n' + toHex(f.contentHash) + '\n';
  return contentHash(key.data(), key.size());
}

std::string ocioCacheFolder(const OcioConfigData& config, std::string& error) {
  if (!config.loaded()) {
    error = config.fileName + ": the config's data is not loaded";
    return {};
  }
  const fs::path dir = userCacheFolder("hybridscape-ocio") / toHex(config.contentHash);
  for (const OcioFile& f : config.files) {
    if (!ocioBundlePathSafe(f.path)) {
      error = config.fileName + ": '" + f.path + "' is no path inside the config's bundle";
      return {};
    }
    std::string why;
    if (!writeCacheFile(dir / f.path, *f.bytes, why)) {
      error = config.fileName + ": cannot write the config for OpenColorIO: " + why;
      return {};
    }
  }
  return dir.string();
}

OCIO::ConstConfigRcPtr ocioConfigOf(const OcioConfigData& config, std::string& error) {
  const std::string dir = ocioCacheFolder(config, error);
  if (dir.empty()) return {};
  try {
    const OCIO::ConstConfigRcPtr read = OCIO::Config::CreateFromFile((fs::path(dir) / kOcioConfigEntry).c_str());
    // The config's own search paths pointed at their copies in the bundle
    // (search<i>/), in its order: OpenColorIO finds its LUTs there.
    OCIO::ConfigRcPtr c = read->createEditableCopy();
    const int n = std::max(1, read->getNumSearchPaths());  // none: the config's folder (readOcioConfig)
    c->clearSearchPaths();
    for (int i = 0; i < n; ++i) c->addSearchPath(("search" + std::to_string(i)).c_str());
    c->setWorkingDir(dir.c_str());
    return c;
  } catch (const std::exception& e) {
    error = config.fileName + ": " + ocioMessage(e.what(), dir, config.fileName);
    return {};
  }
}

OCIO::ConstProcessorRcPtr viewTransformProcessor(const OcioConfigData& config, const std::string& display,
                                                 const std::string& view, std::string& error) {
  const DisplayView dv = resolveDisplayView(config, display, view, error);
  if (!error.empty()) return {};
  const OCIO::ConstConfigRcPtr c = ocioConfigOf(config, error);
  if (!c) return {};
  try {
    const bool aces = c->hasRole(OCIO::ROLE_INTERCHANGE_SCENE);
    OCIO::GroupTransformRcPtr group = OCIO::GroupTransform::Create();
    if (aces) {
      // The renderer's light is linear Rec.709 (sRGB primaries, D65): to
      // ACES2065-1 (AP0, D60, Bradford adaptation), the matrix ACES's own
      // configs use for "Linear Rec.709 (sRGB)".
      const double m[16] = {0.4397010, 0.3829780, 0.1773350, 0.0,  //
                            0.0897923, 0.8134230, 0.0967616, 0.0,  //
                            0.0175440, 0.1115440, 0.8707040, 0.0,  //
                            0.0,       0.0,       0.0,       1.0};
      OCIO::MatrixTransformRcPtr toAces = OCIO::MatrixTransform::Create();
      toAces->setMatrix(m);
      group->appendTransform(toAces);
    }
    OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
    t->setSrc(aces ? OCIO::ROLE_INTERCHANGE_SCENE : OCIO::ROLE_SCENE_LINEAR);
    t->setDisplay(dv.display.c_str());
    t->setView(dv.view.c_str());
    group->appendTransform(t);
    return c->getProcessor(group);
  } catch (const std::exception& e) {
    error = config.fileName + ": display '" + dv.display + "', view '" + dv.view + "': " + e.what();
    return {};
  }
}

OcioConfigSummary ocioSummary(const OcioConfigData& config) {
  if (config.empty()) {
    OcioConfigSummary none;
    none.error = "no OpenColorIO config is stored";
    return none;
  }
  if (!config.loaded()) {  // not kept: the same config, loaded, reads
    OcioConfigSummary none;
    none.error = config.fileName + ": the config's data is not loaded";
    return none;
  }
  static std::mutex mutex;
  static std::map<uint64_t, OcioConfigSummary> known;
  {
    std::lock_guard lock(mutex);
    if (auto it = known.find(config.contentHash); it != known.end()) return it->second;
  }
  OcioConfigSummary s = summarise(config);
  std::lock_guard lock(mutex);
  if (known.size() > 16) known.clear();  // a session imports a few
  return known[config.contentHash] = s;
}

DisplayView resolveDisplayView(const OcioConfigData& config, const std::string& display, const std::string& view,
                               std::string& error) {
  error.clear();
  const OcioConfigSummary s = ocioSummary(config);
  if (!s.error.empty()) {
    error = s.error;
    return {};
  }
  DisplayView out{display.empty() ? s.defaultDisplay : display, view};
  const auto d = std::find_if(s.displays.begin(), s.displays.end(),
                              [&](const OcioDisplay& x) { return x.name == out.display; });
  if (d == s.displays.end()) {
    std::vector<std::string> names;
    for (const OcioDisplay& x : s.displays) names.push_back(x.name);
    error = config.fileName + ": no display '" + out.display + "' (it has " + joined(names) + ")";
    return {};
  }
  if (out.view.empty()) out.view = d->defaultView;
  if (std::find(d->views.begin(), d->views.end(), out.view) == d->views.end()) {
    error = config.fileName + ": display '" + d->name + "' has no view '" + out.view + "' (it has " +
            joined(d->views) + ")";
    return {};
  }
  return out;
}

std::string displayViewProblem(const OcioConfigData& config, const std::string& display, const std::string& view) {
  if (config.empty() || !config.loaded()) return "";
  const OcioConfigSummary s = ocioSummary(config);
  if (!s.error.empty()) return "";  // the renderer reports an unreadable config
  std::string error;
  resolveDisplayView(config, display, view, error);
  return error;
}

std::string ocioConfigProblem(const std::string& where, const OcioConfigData& config) {
  if (config.files.empty() || config.files.front().path != kOcioConfigEntry)
    return where + ": the bundle holds no config";
  if (!config.loaded()) return where + ": the config's data is not loaded";
  size_t total = 0;
  for (const OcioFile& f : config.files) total += f.bytes->size();
  if (total > kMaxOcioBundleBytes || config.files.size() > kMaxOcioFiles)
    return where + ": its search paths hold " + std::to_string(config.files.size()) + " LUT files, " +
           std::to_string(total >> 20) + " MB; a stored config may have " + std::to_string(kMaxOcioFiles) +
           " files and " + std::to_string(kMaxOcioBundleBytes >> 20) + " MB";
  std::string error;
  const OCIO::ConstConfigRcPtr c = ocioConfigOf(config, error);
  if (!c) return where + ": OpenColorIO cannot read it: " + error;
  try {
    c->validate();
  } catch (const std::exception& e) {
    return where + ": OpenColorIO finds it invalid: " + ocioMessage(e.what(), "", "");
  }
  if (!c->hasRole(OCIO::ROLE_SCENE_LINEAR) && !c->hasRole(OCIO::ROLE_INTERCHANGE_SCENE))
    return where + ": it has neither a 'scene_linear' nor an 'aces_interchange' role, so the renderer's linear "
                   "light has no colour space to enter it as";
  if (c->getNumDisplays() == 0) return where + ": it has no active display";
  const OCIO::ConstProcessorRcPtr p = viewTransformProcessor(config, "", "", error);
  if (!p) return where + ": " + error;
  try {
    // Scene light from black to far over white: every output finite.
    const float levels[] = {0.0f, 0.002f, 0.02f, 0.18f, 0.5f, 1.0f, 4.0f, 16.0f, 64.0f};
    const OCIO::ConstCPUProcessorRcPtr cpu = p->getDefaultCPUProcessor();
    for (float b : levels)
      for (float g : levels)
        for (float r : levels) {
          float rgb[3] = {r, g, b};
          cpu->applyRGB(rgb);
          if (!std::isfinite(rgb[0]) || !std::isfinite(rgb[1]) || !std::isfinite(rgb[2]))
            return where + ": its default view gives a non-finite colour for the scene colour (" + std::to_string(r) +
                   ", " + std::to_string(g) + ", " + std::to_string(b) + ")";
        }
  } catch (const std::exception& e) {
    return where + ": OpenColorIO cannot apply its default view: " + e.what();
  }
  return "";
}

std::optional<OcioConfigData> readOcioConfig(const std::string& path, std::string& error,
                                             const Progress* progress) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    error = path + ": a folder, not an OpenColorIO config";
    return std::nullopt;
  }
  OcioConfigData out;
  out.fileName = fs::path(path).filename().string();
  auto text = std::make_shared<std::string>();
  if (!readWhole(path, *text)) {
    error = path + ": cannot open it";
    return std::nullopt;
  }
  if (text->empty()) {
    error = path + ": the file is empty";
    return std::nullopt;
  }
  out.files.push_back({kOcioConfigEntry, nullptr, contentHash(text->data(), text->size())});
  out.files.back().bytes = std::move(text);
  // Where the config looks for its LUTs, as OpenColorIO resolves them at
  // the config's place (its environment variables, its folder).
  OCIO::ConstConfigRcPtr config;
  try {
    config = OCIO::Config::CreateFromFile(path.c_str());
  } catch (const std::exception& e) {
    error = path + ": OpenColorIO cannot read it: " + ocioMessage(e.what(), "", "");
    return std::nullopt;
  }
  const std::vector<std::string> extensions = lutFileExtensions();
  const fs::path working = config->getWorkingDir();
  size_t total = out.files.front().bytes->size();
  // A config without a search path finds its files beside it, as OpenColorIO does.
  const int searchPaths = std::max(1, config->getNumSearchPaths());
  for (int i = 0; i < searchPaths; ++i) {
    const std::string written = config->getNumSearchPaths() ? config->getSearchPath(i) : ".";
    fs::path dir = config->getCurrentContext()->resolveStringVar(written.c_str());
    if (dir.is_relative()) dir = working / dir;
    if (!fs::is_directory(dir, ec)) continue;  // OpenColorIO skips it too; the check below finds a LUT it lacks
    std::vector<fs::path> found;
    fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
      if (it.depth() > 8) it.disable_recursion_pending();  // LUT folders are shallow; a loop of links is not
      if (it->is_regular_file(ec) && lutExtension(it->path(), extensions)) found.push_back(it->path());
      if (found.size() + out.files.size() > kMaxOcioFiles) break;
    }
    std::sort(found.begin(), found.end());  // the same bundle (and hash) on any machine
    for (size_t f = 0; f < found.size(); ++f) {
      const fs::path& file = found[f];
      reportProgress(progress, 0.8 * (double(i) + double(f) / double(found.size())) / double(searchPaths),
                     "Reading " + file.filename().string());
      if (isCancelled(progress)) {
        error = path + ": the import was cancelled";
        return std::nullopt;
      }
      auto bytes = std::make_shared<std::string>();
      if (!readWhole(file, *bytes)) {
        error = file.string() + ": cannot read it (a LUT under search path '" + written + "' of " + path + ")";
        return std::nullopt;
      }
      total += bytes->size();
      if (total > kMaxOcioBundleBytes || out.files.size() >= kMaxOcioFiles) {
        error = path + ": its search paths hold more than " + std::to_string(kMaxOcioFiles) + " LUT files or " +
                std::to_string(kMaxOcioBundleBytes >> 20) +
                " MB, more than a stored config may have (point its search_path at the LUT folders only)";
        return std::nullopt;
      }
      const std::string inside = "search" + std::to_string(i) + "/" + fs::relative(file, dir, ec).generic_string();
      out.files.push_back({inside, nullptr, contentHash(bytes->data(), bytes->size())});
      out.files.back().bytes = std::move(bytes);
    }
  }
  out.contentHash = ocioBundleHash(out.files);
  reportProgress(progress, 0.8, "Checking the config");
  if (std::string p = ocioConfigProblem(path, out); !p.empty()) {
    error = p;
    return std::nullopt;
  }
  return out;
}

const OperationDecl& ocioImportOperation() {
  static const OperationDecl op{
      .name = "ocio import",
      .summary = "view the scene through an OpenColorIO config's display/view transform (stored in the scene)",
      .usage = "<config.ocio> <scene.hscene>",
      .description =
          "Reads an OpenColorIO config with the LUT files under its search paths, stores them in the scene (a "
          "render node needs no copy of the studio's folder) and turns settings.post.view_transform.enabled on "
          "at the config's default display and view. The view transform takes the tone map's place in the chain: "
          "the renderer's linear Rec.709 light enters as the config's 'aces_interchange' colour space (converted "
          "to ACES2065-1) or, without one, as its 'scene_linear' role (docs/rendering.md, \"Post-processing\"). A "
          "scene holds one config: importing another replaces it.",
      .notes = "Choose a display and view with: hybridscape-cli ocio list scene.hscene, then\n"
               "  hybridscape-cli set settings.post.view_transform.view \"Filmic\" scene.hscene",
      .positionals = {{.name = "config.ocio", .help = "the OpenColorIO config file"},
                      {.name = "scene.hscene", .help = "the scene file"}},
  };
  return op;
}

const OperationDecl& ocioClearOperation() {
  static const OperationDecl op{
      .name = "ocio clear",
      .summary = "remove the scene's OpenColorIO config",
      .usage = "<scene.hscene>",
      .description = "Removes the stored config and turns settings.post.view_transform.enabled off (the tone map "
                     "in settings.tonemap applies again).",
      .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
  };
  return op;
}

const OperationDecl& ocioListOperation() {
  static const OperationDecl op{
      .name = "ocio list",
      .summary = "list the displays and views of the scene's OpenColorIO config",
      .usage = "<scene.hscene>",
      .description = "Prints the stored config's name, the colour space the renderer's light enters it as, its "
                     "active displays and their views (the defaults and the chosen pair marked), and its files.",
      .positionals = {{.name = "scene.hscene", .help = "the scene file"}},
  };
  return op;
}

namespace ops {
bool setOcioConfig(Document& doc, const OcioConfigData& config) {
  Edit e(doc, config.empty() ? QString("Remove OpenColorIO config")
                             : QString("Import OpenColorIO config %1").arg(QString::fromStdString(config.fileName)));
  e.settings().post.ocioConfig = config;
  e.settings().post.viewTransform = !config.empty();
  e.settings().post.display.clear();
  e.settings().post.view.clear();
  return e.commit();
}
}  // namespace ops

}  // namespace hs::scene
