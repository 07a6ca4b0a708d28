#include "meshproc/lod_chain.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace hs::mesh {

double projectedErrorPixels(double errorMetres, double distance, double fovY, double viewportHeight) {
  if (!(distance > 0) || !(fovY > 0)) return HUGE_VAL;
  // A length e at distance d covers e / (2 d tan(fov/2)) of the view height.
  return errorMetres * viewportHeight / (2.0 * distance * std::tan(0.5 * fovY));
}

double lodDistance(double errorMetres, double fovY, double viewportHeight, double thresholdPixels) {
  if (!(thresholdPixels > 0) || !(fovY > 0) || !(viewportHeight > 0)) return HUGE_VAL;
  return errorMetres * viewportHeight / (2.0 * std::tan(0.5 * fovY) * thresholdPixels);
}

int selectLod(const std::vector<double>& errors, double distance, double fovY, double viewportHeight,
              double thresholdPixels) {
  int chosen = 0;
  for (size_t i = 0; i < errors.size(); ++i)
    if (projectedErrorPixels(errors[i], distance, fovY, viewportHeight) <= thresholdPixels)
      chosen = int(i);
    else
      break;  // errors grow along the chain: no coarser level can pass
  return chosen;
}

LodChain buildLodChain(const MeshData& base, const LodOptions& options, const Progress* progress) {
  LodChain chain;
  Lod first;
  first.mesh = base;
  first.triangles = base.triangleCount();
  chain.levels.push_back(std::move(first));
  if (options.levels <= 0 || base.triangleCount() == 0) return chain;

  const ErrorMeter meter(base, options.error);
  const int levels = options.levels;
  for (int level = 1; level <= levels; ++level) {
    const MeshData& prev = chain.levels.back().mesh;
    const size_t want = size_t(std::llround(double(prev.triangleCount()) * std::clamp(options.ratio, 0.0, 1.0)));
    if (want < options.minTriangles || want >= prev.triangleCount()) break;
    const double span = 1.0 / double(levels);
    // Forwards progress into this level's slice, and the user's Cancel into
    // the level's own flag (decimate and measure poll that one).
    Progress* self = nullptr;
    Progress sub([&](double f, std::string_view stage) {
      reportProgress(progress, (double(level - 1) + f) * span, stage);
      if (self && isCancelled(progress)) self->cancel();
    });
    self = &sub;
    if (isCancelled(progress)) sub.cancel();

    DecimateOptions d = options.decimate;
    d.targetTriangles = want;
    d.copyTextures = false;
    const auto t0 = std::chrono::steady_clock::now();
    DecimateResult r = decimate(prev, d, progress ? &sub : nullptr);
    const auto t1 = std::chrono::steady_clock::now();
    if (r.cancelled || isCancelled(progress)) {
      chain.cancelled = true;
      return chain;
    }
    if (!r.ok()) {
      chain.error = "level " + std::to_string(level) + ": " + r.error;
      return chain;
    }
    if (r.mesh.triangleCount() >= prev.triangleCount()) break;  // nothing more to take
    double refineSeconds = 0;
    if (options.refine) {
      RefineOptions ro = options.refinement;
      ro.threads = d.threads;
      const RefineReport rr = refineMaxError(meter, r.mesh, ro, progress ? &sub : nullptr);
      if (rr.cancelled) {
        chain.cancelled = true;
        return chain;
      }
      refineSeconds = rr.seconds;
    }
    const ErrorReport e = meter.measure(r.mesh, progress ? &sub : nullptr);
    if (e.cancelled) {
      chain.cancelled = true;
      return chain;
    }
    Lod lod;
    lod.triangles = r.mesh.triangleCount();
    // A level is never reported better than the one before it: the
    // selection rule relies on errors growing along the chain.
    lod.hausdorff = std::max(e.hausdorff, chain.levels.back().hausdorff);
    lod.hausdorffRel = e.rel(lod.hausdorff);
    lod.meanError = e.mean;
    lod.samplesPerFace = e.samplesPerFace;
    lod.decimateSeconds = std::chrono::duration<double>(t1 - t0).count();
    lod.refineSeconds = refineSeconds;
    lod.errorSeconds = e.seconds;
    lod.mesh = std::move(r.mesh);
    chain.levels.push_back(std::move(lod));
  }
  return chain;
}

}  // namespace hs::mesh
