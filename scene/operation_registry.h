#pragma once
// Every operation the editor and the command line share, declared once
// (core/params.h), in one list: for --help and for the tests that drive
// both frontends at each parameter's bounds (tests/cli/test_cli_params,
// tests/app/test_editor_params), so a new operation is checked as soon as
// it is listed here.
#include <vector>

#include "core/params.h"

namespace hs::scene {

// import, mesh export, terrain new/import/erode/paint-rules/layer/export, render,
// sequence, key, path, farm slurm, farm verify, repair, light add, foliage type
// add/scatter/clear/plant, particles add.
const std::vector<const OperationDecl*>& sharedOperations();
// The operation named `name` ("terrain erode"); nullptr if none.
const OperationDecl* findOperation(std::string_view name);

}  // namespace hs::scene
