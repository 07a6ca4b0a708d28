#include "render/frame_stats_json.h"

namespace hs::render {
namespace {

Json milliseconds(double ms) { return ms >= 0.0 ? Json(ms) : Json(nullptr); }

}  // namespace

Json frameStatsJson(const FrameStats& stats, const std::vector<GpuAllocation>& registry) {
  Json passes = Json::array();
  for (const PassStats& p : stats.passes)
    passes.push_back({{"name", p.name}, {"cpu_ms", p.cpuMs}, {"gpu_ms", milliseconds(p.gpuMs)}, {"gpu_bytes", p.gpuBytes}});
  Json resources = Json::array();
  size_t bytes = 0;
  for (const GpuAllocation& a : registry) {
    resources.push_back({{"name", a.name}, {"kind", a.kind}, {"bytes", a.bytes}, {"transient", a.transient}});
    if (a.users.size() > 1) resources.back()["users"] = a.users;  // pooled memory several resources used in turn
    bytes += a.bytes;
  }
  Json j;
  j["passes"] = std::move(passes);
  j["gpu_bytes"] = bytes;
  j["idle_gpu_bytes"] = stats.idleGpuBytes;  // pooled, unused this frame, kept for reuse
  j["triangles"] = stats.trianglesDrawn;
  j["draw_calls"] = stats.drawCalls;
  j["instances_drawn"] = stats.instancesDrawn;
  j["particles_drawn"] = stats.particlesDrawn;
  j["emitters_out_of_view"] = stats.emittersOutOfView;
  j["instances_culled"] = stats.instancesCulled;
  j["cpu_ms"] = stats.cpuMs;
  // The frame's timer query answers an earlier frame; with per-pass
  // timestamps this frame's GPU time is their sum.
  double passGpu = stats.passes.empty() ? -1.0 : 0.0;
  for (const PassStats& p : stats.passes) passGpu = (passGpu < 0.0 || p.gpuMs < 0.0) ? -1.0 : passGpu + p.gpuMs;
  j["gpu_ms"] = milliseconds(passGpu >= 0.0 ? passGpu : stats.gpuMs);
  j["lights"] = {{"in_view", stats.lightsInView},
                 {"clusters_over_cap", stats.lightClustersOverCap},
                 {"max_per_cluster", stats.lightsMaxPerCluster}};
  // Transparency (render/oit.h): null when no translucent surface was in view.
  if (stats.oit.active) {
    const OitStats& o = stats.oit;
    j["oit"] = {{"mode", o.mode},
                {"bytes", o.bytes},
                {"fragments", o.counted ? Json(o.fragments) : Json(nullptr)},
                {"fragments_per_pixel_max", o.counted ? Json(o.maxPerPixel) : Json(nullptr)},
                {"fragments_per_pixel_mean", o.counted ? Json(o.meanPerPixel) : Json(nullptr)},
                {"covered_pixels", o.counted ? Json(o.coveredPixels) : Json(nullptr)},
                {"overflow", o.overflow},
                {"tail_share", o.tailShare},
                {"tail_pixels", o.tailPixels},
                {"layers", o.layers},
                {"peels", o.peels}};
  } else {
    j["oit"] = nullptr;
  }
  // Cluster hierarchies (render/cluster_source.h): null when none was drawn.
  if (const ClusterStats& c = stats.clusters; c.instances > 0 || c.pagesWanted > 0) {
    j["clusters"] = {{"instances", c.instances},         {"clusters", c.clusters},
                     {"triangles", c.triangles},         {"pages_resident", c.pagesResident},
                     {"pages_drawn", c.pagesDrawn},      {"pages_wanted", c.pagesWanted},
                     {"pages_loading", c.pagesLoading},  {"gpu_bytes", c.gpuBytes},
                     {"cpu_bytes", c.cpuBytes},          {"complete", c.complete},
                     {"budget_full", c.budgetFull},      {"cut_ms", c.cutMs}};
  } else {
    j["clusters"] = nullptr;
  }
  j["resources"] = std::move(resources);
  return j;
}

}  // namespace hs::render
