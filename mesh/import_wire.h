#pragma once
// What the import worker (tools/import_worker, `hybridscape-import-worker`)
// and the process that started it (scene/import_isolation.h) say to each
// other. Plain C++ on top of hs_mesh, no Qt: the worker stays small.
//
//   parent -> worker  the file and the ImportOptions, as arguments
//                     (importWorkerArguments / parseImportWorkerArguments);
//                     a worker kept for several files (--serve) gets each
//                     file's arguments as a request on its stdin instead
//                     (importRequest / readImportRequest) and ends at the
//                     end of its stdin
//   worker -> parent  progress, one line each on stdout:
//                       "progress <fraction> <stage>\n"
//                     the ImportResult (mesh with its textures, report, error)
//                     written to a file descriptor the parent hands over
//                     (writeImportResult / readImportResult); a serving
//                     worker rewrites it from the start for each request
//                     and then says "done\n" on stdout
//
// The result is a small header, the report, then the mesh's arrays as they
// are in memory (little-endian, the same machine wrote it), ended by a
// trailer: a worker that died while writing leaves no trailer, and reading
// checks every size against the bytes present, so a torn result is an error,
// never a crash.
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh_import.h"

namespace hs::mesh {

// The worker's arguments for reading `path` with `options` (without the
// program name), and their parsing on the worker's side.
std::vector<std::string> importWorkerArguments(const std::string& path, const mesh::ImportOptions& options);
bool parseImportWorkerOptionArgument(const std::string& key, const std::string& value, mesh::ImportOptions& options,
                                     std::string& error);

// One request to a serving worker: the arguments importWorkerArguments
// gives, framed so that any byte (a newline in a path) passes:
//   "request <count>\n" then, per argument, "<length>\n<bytes>\n".
std::string importRequest(const std::vector<std::string>& args);
// Reads one request from `in`; false at the end of `in` (`error` empty) or
// on a malformed one (`error` says what).
bool readImportRequest(std::FILE* in, std::vector<std::string>& args, std::string& error);
// What a serving worker says on stdout once a result is written.
inline constexpr std::string_view kImportDoneLine = "done";

// One progress line, with the newline; and its parsing (false if `line` is
// not a progress line).
std::string importProgressLine(double fraction, std::string_view stage);
bool parseImportProgressLine(std::string_view line, double& fraction, std::string& stage);

// Writes `result` to `out`; false (with errno set by stdio) if it could not.
bool writeImportResult(std::FILE* out, const mesh::ImportResult& result);
// Reads a result written by writeImportResult from the start of `in`.
// False (and `error`, without a file name) if it is missing, torn or damaged.
bool readImportResult(std::FILE* in, mesh::ImportResult& result, std::string& error);

}  // namespace hs::mesh
