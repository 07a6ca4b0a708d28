#pragma once
// Loading a module of this project (a shared object opened with dlopen on
// first use) that wraps a library too heavy to load at every process start:
// OpenImageIO (core/image_io.h) and GDAL (terrain/gdal_door.h). One loader
// for both, so both look in the same places, in the same order, and say the
// same things when the module is not there.
//
// The module is looked for at $<envVar> when that is set (and only there),
// else at the path the build gave it, else beside the running program. Its
// entry point, `entrySymbol` (extern "C", no arguments), returns a pointer
// to its calls; the module stays loaded for the rest of the process.
#include <string>

namespace hs {

struct ModuleSpec {
  const char* fileName;     // "hybridscape-gdal.so"
  const char* envVar;       // "HS_GDAL_MODULE"
  const char* buildPath;    // where the build put it; nullptr when unknown
  const char* entrySymbol;  // "hs_gdal_backend"
  const char* kind;         // "GDAL module", for messages
  const char* wraps;        // "GDAL", what it wraps, for messages
  const char* without;      // "no elevation model can be imported", what fails without it
};

struct LoadedModule {
  const void* entry = nullptr;  // what the entry point returned; nullptr when not loaded
  // The module's path; or, when it was not loaded, a message saying which
  // module is missing, what fails without it, where it was looked for and
  // why each place failed, and which variable names it.
  std::string where;

  // The entry's calls as the door's `Calls`, or nullptr with `error` set to
  // `where` (why there are none).
  template <class Calls>
  const Calls* calls(std::string& error) const {
    if (!entry) error = where;
    return static_cast<const Calls*>(entry);
  }
  // Whether it loaded; `whereOut` gets `where`.
  bool available(std::string* whereOut) const {
    if (whereOut) *whereOut = where;
    return entry != nullptr;
  }
};

// Called on the loading thread just before dlopen (true) and just after
// (false): the import worker lifts its address-space limit around it.
using ModuleLoadHook = void (*)(bool before);

// Tries each place in turn; never throws. Callers keep the result (a
// function-local static) so that a module is opened once per process.
LoadedModule loadModule(const ModuleSpec& spec, ModuleLoadHook hook = nullptr);

}  // namespace hs
