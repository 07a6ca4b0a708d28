#pragma once
// `hybridscape-cli import`'s options turned into a scene::MeshImportRequest:
// the reader's (--up, --reader, --origin, --strict-textures) and the
// processing ones (--decimate-to, --max-error, --lods, --clean), all
// declared in scene::meshImportOperation(). Each bad value is a one-line
// error naming the option.
#include <string>

#include "cli/operation_options.h"
#include "scene/import_pipeline.h"

namespace hs::cli {

// Fills `request` (files are the caller's). False with `error` on a bad value.
bool parseImportRequest(const OperationArgs& args, scene::MeshImportRequest& request, std::string& error);

}  // namespace hs::cli
