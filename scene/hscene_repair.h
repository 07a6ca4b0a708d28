#pragma once
// "Save a repaired copy": what can still be read from a damaged scene file,
// written to a new file. For a file that opening refuses as damaged (a
// corrupted blob, an unreadable description, a file cut short), the user's
// work is salvaged instead of lost: the description if it still reads, each
// mesh whose data still matches its hash, the terrains if their tiles do,
// and a list of what was dropped and why. The damaged file is never
// written: the salvage reads a private copy of it.
#include <string>
#include <vector>

#include "core/params.h"

namespace hs::scene {

struct RepairReport {
  bool wasWhole = false;              // the file opened as it is: the copy holds everything
  std::vector<std::string> notes;     // what opening the copy said (recovered journal, clamped values)
  std::vector<std::string> dropped;   // one line per thing lost, with the reason
  size_t entities = 0, meshes = 0, terrains = 0;  // what the repaired copy holds
};

// Salvages `damaged` into `out`. Refuses (false, `error` naming the file)
// when `out` exists or is `damaged`, when `damaged` is not an SQLite file at
// all, or when the copy cannot be written. Otherwise true, even when much
// was dropped: `report` says what.
bool repairScene(const std::string& damaged, const std::string& out, RepairReport& report, std::string& error);

// `hybridscape-cli repair DAMAGED OUT` (and the editor's File > Repair...).
const OperationDecl& repairOperation();

}  // namespace hs::scene
