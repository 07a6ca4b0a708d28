#pragma once
// One frame's statistics as JSON, written by `hybridscape-cli render --stats`
// and read by whoever checks a render (tests, scripts, a farm's logs):
//   {"passes": [{"name", "cpu_ms", "gpu_ms", "gpu_bytes"}], "gpu_bytes",
//    "triangles", "draw_calls", "cpu_ms", "gpu_ms", "resources": [...]}
// `passes` lists only the passes that ran (a culled pass is absent), in the
// order they ran; a pass's gpu_bytes are the transient resources it first
// used. `gpu_bytes` and `resources` are the renderer's registry
// (Renderer::resourceRegistry()): what is allocated, not what passes say.
// gpu_ms is null where it was not measured (no timer queries); the frame's
// gpu_ms is the sum of its passes' when each was measured.
#include <vector>

#include "core/json.h"
#include "render/renderer.h"

namespace hs::render {

Json frameStatsJson(const FrameStats& stats, const std::vector<GpuAllocation>& registry);

}  // namespace hs::render
