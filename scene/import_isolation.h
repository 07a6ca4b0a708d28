#pragma once
// Reading mesh files that go through Assimp in a process of their own.
// Debian 12's Assimp 5.2.5 crashes (double free, abort, segfault) on some
// damaged files; in the editor that would end the session with its unsaved
// work. So every file importMesh would hand to Assimp (FBX, PLY, glTF, DAE,
// 3DS, STL, ...) is read by `hybridscape-import-worker`
// (tools/import_worker), which sends back the mesh with its textures, the
// report and progress (scene/import_wire.h). A crash becomes an error naming
// the file; Cancel kills the worker. The own OBJ reader and
// importObjFromMemory stay in this process. docs/meshes.md, "Isolation".
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_import.h"

namespace hs::scene {

// True if importMesh would read `path` with Assimp (not the own OBJ reader):
// such files are read by the worker.
bool readsWithAssimp(const std::string& path, const mesh::ImportOptions& options);

// The worker program: $HS_IMPORT_WORKER when set (and not empty), else the
// one built with this program, else one beside the running executable.
// Empty if none is there; `lookedAt` then lists where it looked.
std::string findImportWorker(std::string* lookedAt = nullptr);

// What the worker may use. It runs under a memory limit (RLIMIT_AS on
// what it maps beyond its own libraries), a share of the memory this
// process may use (core/memory_limit.h: the machine's, or its control
// group's limit where lower, as in a Slurm job or a container), so a file
// that asks for too much stops with an error saying so instead of taking
// the machine or getting the job killed; and under a watchdog that stops
// it when it reports no progress for a while (a reader spinning on a
// damaged file). Set by the environment:
//   HS_IMPORT_MEMORY_LIMIT  "50%" of that memory (the default), a
//                           number of MiB ("4096"), or "0": no limit
//   HS_IMPORT_WATCHDOG_S    seconds without progress (default 300), "0": none
struct WorkerLimits {
  uint64_t memoryBytes = 0;     // 0: none
  std::string memoryText;       // how it was set, for messages ("50% of 125.8 GiB")
  uint64_t usableBytes = 0;     // what a share is of (core/memory_limit.h's memoryLimit().bytes)
  double watchdogSeconds = 0;   // 0: none
};
// False with `error` naming the variable when one is set to nonsense.
bool workerLimits(WorkerLimits& limits, std::string& error);

// How many tiles of one import to read at once (mesh::TileImportOptions::
// maxParallel). 1 when no tile goes through the worker: the own OBJ and PLY
// readers already use every core on one file, and reading two at once
// would only raise the peak memory. Otherwise one worker per tile read at
// once (ImportWorkerPool keeps it for the next tile), as many at once as
// this process may use CPUs (availableThreads) and as fit the machine's
// memory under the workers' limit (usable memory / HS_IMPORT_MEMORY_LIMIT:
// 2 at the default 50%; every available CPU with the limit off).
unsigned tileReadParallelism(const std::vector<std::string>& paths, const mesh::ImportOptions& options);

// Workers kept for the files of one import (a multi-tile scan): each read
// takes an idle worker or starts one, and gives it back when it is still
// fine afterwards, so N tiles read k at a time start k workers, not N (each
// costs about 0.2 s to start). A worker that crashed, hung or was
// cancelled is gone; the next read starts another. Safe to call from
// several threads at once. The workers end with the pool.
class ImportWorkerPool {
 public:
  ImportWorkerPool();
  ~ImportWorkerPool();
  ImportWorkerPool(const ImportWorkerPool&) = delete;
  ImportWorkerPool& operator=(const ImportWorkerPool&) = delete;

  // importMeshIsolated's reading, on this pool's workers.
  mesh::ImportResult read(const std::string& path, const mesh::ImportOptions& options,
                          const Progress* progress = nullptr);
  // How many worker processes this pool has started so far.
  unsigned workersStarted() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// mesh::importMesh, with the files Assimp reads read by the worker. Without a
// worker the file is read here, with a warning in the report saying so. The
// report's `seconds` is the whole time, starting the worker included.
mesh::ImportResult importMeshIsolated(const std::string& path, const mesh::ImportOptions& options,
                                      const Progress* progress = nullptr);

}  // namespace hs::scene
