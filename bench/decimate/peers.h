#pragma once
// Other tools' decimators as peers of bench_decimate (issue 11 item 5):
// Blender 3.4's Decimate modifier (collapse) run headless, and MeshLab
// 2020.09's "Quadric Edge Collapse Decimation" through meshlabserver (under
// xvfb-run: it needs an X display). Each gets the same surface: positions
// welded (so UV seams do not cut it) and, for Blender, the UVs per corner;
// the result is read back with our importer into the input's frame, so the
// same error code measures every method. A tool that is not installed is
// skipped with a note (how they run here: /work/shared/notes/
// verified-on-this-machine.md).
#include <string>

#include "mesh/mesh_data.h"

namespace hs::bench {

struct PeerRun {
  bool ran = false;
  std::string note;              // why it did not run, or what the time covers
  hs::mesh::MeshData mesh;       // in the input's frame (its origin)
  double seconds = 0.0;          // the decimation (see note)
};

// Blender: the time is the modifier's apply, measured inside Blender
// (import, export and Blender's start are not counted).
PeerRun runBlenderDecimate(const hs::mesh::MeshData& in, double ratio, const std::string& workDir);
// MeshLab: meshlabserver prints no filter time, so the time is the
// process's wall time with the filter minus the same process without it
// (load and save only); both include a loaded machine's noise.
PeerRun runMeshlabDecimate(const hs::mesh::MeshData& in, size_t targetTriangles, const std::string& workDir);

}  // namespace hs::bench
