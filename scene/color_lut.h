#pragma once
// Colour look-up tables in the document (docs/rendering.md "Post-processing",
// LUTs): reading one from a file, checking its bytes, and the settings edit
// that grades a scene with it. OpenColorIO parses and applies them (it
// reads .cube, .3dl, .spi3d, .spi1d, .csp, .clf and more): no LUT parser
// of our own. OpenColorIO reads LUTs only from files, so a LUT's bytes are
// written once to a per-user cache folder named by their hash
// (lutCacheFile) and handed to it from there; the document keeps the bytes.
#include <optional>
#include <string>
#include <vector>

#include "core/params.h"
#include "scene/scene_state.h"

namespace hs::scene {

class Document;

// Larger files are refused: a 256^3 float LUT, the most OpenColorIO takes,
// is about 200 MB as text.
constexpr size_t kMaxLutFileBytes = size_t(512) << 20;

// Reads `path` as a LUT: its bytes, name and hash, after lutProblem finds
// nothing wrong. On failure nullopt and `error` names the file (and the
// line where the fault is on one).
std::optional<LutData> readLutFile(const std::string& path, std::string& error);

// Why `lut` (its bytes and their hash, from a file named lut.fileName) is
// no LUT the renderer can apply, as a message starting with `where`; "" if
// it is one.
// Checks: not empty, under kMaxLutFileBytes, no non-finite number in a text
// format (named with its line), OpenColorIO parses it (its message, which
// names the line for text formats), and every output over a 17^3 lattice of
// inputs in [0, 1] is finite.
std::string lutProblem(const std::string& where, const LutData& lut);

// The file OpenColorIO reads `lut` from: <temp>/hybridscape-luts-<user>/
// <hash>.<ext>, written (atomically) when missing. Empty with `error` when
// the folder cannot be written or the LUT has no bytes.
std::string lutCacheFile(const LutData& lut, std::string& error);

// The .hscene blob holding a LUT's bytes: "lut/<hash in hex>".
std::string lutBlobKey(uint64_t contentHash);

// The extensions OpenColorIO reads ("cube", "3dl", ...), for messages and
// the editor's file dialog.
std::vector<std::string> lutFileExtensions();

// `lut import FILE SCENE` (Import LUT... in the Scene Settings dock) and
// `lut clear SCENE` (Remove LUT): their names and help, declared once.
const OperationDecl& lutImportOperation();
const OperationDecl& lutClearOperation();

namespace ops {
// Grades the scene with `lut` (post.lut, post.lut.enabled on) as one undo
// step; an empty LutData removes the LUT and turns it off.
bool setLut(Document& doc, const LutData& lut);
}  // namespace ops

}  // namespace hs::scene
