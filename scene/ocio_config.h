#pragma once
// OpenColorIO configs in the document (docs/rendering.md "Post-processing",
// view transforms): reading a studio's config with the LUT files under its
// search paths into one bundle (OcioConfigData), checking it, listing its
// displays and views, and the settings edit that puts it in the chain.
// OpenColorIO 2.1 reads a config's LUTs only from files (no in-memory
// reader before 2.2), so a bundle is written once to a per-user cache
// folder named by its hash (ocioCacheFolder) and the config is pointed at
// it there (scene/lut_processor.h ocioConfigOf); the document keeps the
// bytes.
#include <optional>
#include <string>
#include <vector>

#include "core/params.h"
#include "core/progress.h"
#include "scene/scene_state.h"

namespace hs::scene {

class Document;

// A bundle's limits: what its search paths may hold in all, and how many
// files. A studio's config with its LUTs is a few MB to a few hundred.
constexpr size_t kMaxOcioBundleBytes = size_t(1) << 30;
constexpr size_t kMaxOcioFiles = 4096;

// The name of the config inside a bundle (OcioConfigData::files[0].path).
inline constexpr const char* kOcioConfigEntry = "config.ocio";

// Reads the config at `path` with every file under its search paths that
// OpenColorIO reads as a LUT (lutFileExtensions), after ocioConfigProblem
// finds nothing wrong with the bundle. On failure nullopt and `error`
// names the file (and what in it is wrong). `progress` hears of each file
// read and of the check; cancelled, nullopt with `error` saying so.
std::optional<OcioConfigData> readOcioConfig(const std::string& path, std::string& error,
                                             const Progress* progress = nullptr);

// The hash over a bundle's files (their paths and content hashes).
uint64_t ocioBundleHash(const std::vector<OcioFile>& files);

// Why `config` is no config the renderer can use, as a message starting
// with `where`; "" if it is one. Checks: its files' data is there,
// OpenColorIO parses and validates it from the bundle alone, it has a
// scene-linear role (or an ACES interchange role) to start from, and the
// default display's default view makes a processor.
std::string ocioConfigProblem(const std::string& where, const OcioConfigData& config);

// The folder the bundle is written to for OpenColorIO: <temp>/
// hybridscape-ocio-<user>/<hash>/, written (atomically, per file) when
// missing. Empty with `error` when it cannot be written.
std::string ocioCacheFolder(const OcioConfigData& config, std::string& error);

// Whether `path` (a bundle file's, from a file or a description) stays
// inside the bundle: relative, no `..` or `.`, no backslash.
bool ocioBundlePathSafe(const std::string& path);

// The .hscene blob holding one file of a bundle: "ocio/<hash in hex>".
std::string ocioBlobKey(uint64_t fileHash);

// What a config offers: its active displays (the default first as the
// config orders them) and each one's active views.
struct OcioDisplay {
  std::string name;
  std::vector<std::string> views;
  std::string defaultView;
};
struct OcioConfigSummary {
  std::vector<OcioDisplay> displays;
  std::string defaultDisplay;
  // The colour space the renderer's linear Rec.709 light enters as:
  // "aces_interchange" (converted to ACES2065-1 first) or "scene_linear".
  std::string sourceRole;
  std::string error;  // why the config could not be read ("" when it was)
};
// Read once per bundle (kept by hash).
OcioConfigSummary ocioSummary(const OcioConfigData& config);

// The display and view `post` asks for, empty names resolved to the
// config's defaults. Empty `error` when both exist in the config; else it
// names the unknown one and lists what there is.
struct DisplayView {
  std::string display, view;
};
DisplayView resolveDisplayView(const OcioConfigData& config, const std::string& display, const std::string& view,
                               std::string& error);

// A settings field's rule (post.view_transform.display / .view): why
// `display` and `view` name nothing in `config`, or "" when they do or
// when there is no config (or its data is not loaded yet) to check with.
std::string displayViewProblem(const OcioConfigData& config, const std::string& display, const std::string& view);

// `ocio import CONFIG SCENE`, `ocio clear SCENE` and `ocio list SCENE`
// (Import OCIO config... / Remove in the Post dock): names and help,
// declared once.
const OperationDecl& ocioImportOperation();
const OperationDecl& ocioClearOperation();
const OperationDecl& ocioListOperation();

namespace ops {
// Puts `config` in the scene with its view transform on at the config's
// default display and view, as one undo step; an empty config removes it
// and turns the view transform off.
bool setOcioConfig(Document& doc, const OcioConfigData& config);
}  // namespace ops

}  // namespace hs::scene
