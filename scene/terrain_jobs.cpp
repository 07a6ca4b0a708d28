#include "scene/terrain_jobs.h"

#include <chrono>
#include <cstdarg>
#include <cstdio>

#include "terrain/undo_step.h"

namespace hs::scene {
namespace {

[[gnu::format(printf, 1, 2)]] std::string fmt(const char* f, ...) {
  char buf[256];
  va_list args;
  va_start(args, f);
  std::vsnprintf(buf, sizeof buf, f, args);
  va_end(args);
  return buf;
}

terrain::ErosionMask maskFor(const terrain::Terrain& t, TerrainJob::Mask m) {
  if (m.paintLayer >= 0) return terrain::ErosionMask::fromPaintLayer(t.paint, m.paintLayer);
  return terrain::ErosionMask::whole(t.height);
}

std::string erosionSummary(const char* what, const terrain::ErosionReport& r) {
  std::string s = std::string(what) + ": " + std::to_string(r.iterationsDone) + " iterations on " +
                  std::to_string(r.changed.width()) + " x " + std::to_string(r.changed.height()) + " samples in " +
                  fmt("%.2f s (%.1f M cell-iterations/s, %d threads); ", r.seconds, r.cellIterationsPerSecond * 1e-6,
                      r.threads) +
                  fmt("mass error %.3g m^3 (relative %.2g)", r.massError, r.relativeMassError);
  if (r.cflLimitedIterations > 0)
    s += fmt("; time step limited by CFL in %.0f iterations (smallest %.3g s, simulated %.3g of %.3g s)",
             double(r.cflLimitedIterations), r.minDt, r.simulatedTime, r.requestedTime);
  return s;
}

}  // namespace

TerrainJob::TerrainJob(const Document& doc, TerrainId id, QString label, Work work)
    : id_(id), label_(std::move(label)), work_(std::move(work)) {
  const TerrainAsset* t = doc.state().findTerrain(id);
  if (!t || !t->data) {
    error_ = "no terrain " + std::to_string(id) + " in the scene";
    return;
  }
  terrainName_ = t->name;
  live_ = t->data;
  bool expected = false;
  if (!live_->jobRunning.compare_exchange_strong(expected, true)) {
    error_ = "terrain '" + t->name + "' is busy with another operation; try again when it has finished";
    live_.reset();
    return;
  }
  // Copy-on-write: O(tiles), and the live terrain stays editable.
  base_ = live_->terrain().clone();
  result_ = live_->terrain().clone();
  valid_ = true;
}

TerrainJob::~TerrainJob() {
  if (valid_ && live_) live_->jobRunning = false;
}

void TerrainJob::run(const Progress* progress, int threads) {
  if (!valid_ || ran_) return;
  ran_ = true;
  step_ = work_(result_, progress, threads, outcome_);
  if (isCancelled(progress)) outcome_.cancelled = true;
}

TerrainJobOutcome TerrainJob::commit(Document& doc) {
  TerrainJobOutcome out = std::move(outcome_);
  if (!valid_) {
    out.error = error_;
    return out;
  }
  live_->jobRunning = false;
  valid_ = false;
  const std::string what = "terrain '" + terrainName_ + "'";
  if (!ran_) {
    out.error = what + ": the operation did not run";
    return out;
  }
  if (out.cancelled || !out.error.empty()) {
    if (!out.error.empty() && out.error.find(what) == std::string::npos) out.error = what + ": " + out.error;
    return out;
  }
  const TerrainAsset* t = doc.state().findTerrain(id_);
  if (!t || t->data != live_) {
    out.error = what + " was deleted while the operation ran; nothing was changed";
    return out;
  }
  if (step_.empty()) {
    out.ok = true;
    if (out.summary.empty()) out.summary = what + ": nothing to change";
    return out;
  }
  if (!step_.unchangedSince(live_->terrain(), base_)) {
    out.error = what + " was edited while the operation ran; its result no longer applies and was not used. "
                       "Run it again.";
    return out;
  }
  const uint8_t kinds = changeKindsOf(step_);
  out.changed = step_.adopt(live_->terrain(), result_);
  live_->noteChanged(out.changed, kinds);
  out.push = pushTerrainStep(doc, id_, std::move(step_), label_);
  doc.notifyTerrainChanged(id_);
  out.ok = true;
  // Drop the copies: later edits of the live tiles need not copy them.
  base_ = terrain::Terrain{};
  result_ = terrain::Terrain{};
  return out;
}

std::unique_ptr<TerrainJob> TerrainJob::thermal(const Document& doc, TerrainId id, const terrain::ThermalParams& p,
                                                Mask mask) {
  Work w = [p, mask](terrain::Terrain& t, const Progress* progress, int threads, TerrainJobOutcome& out) {
    terrain::UndoRecorder rec(t);
    terrain::ErosionReport r = terrain::erodeThermal(t.height, p, maskFor(t, mask), &rec, progress, threads);
    out.warnings = r.warnings;
    out.summary = erosionSummary("thermal erosion", r);
    out.erosion = r;
    return r.cancelled ? terrain::UndoStep{} : rec.finish("Thermal erosion");
  };
  return std::unique_ptr<TerrainJob>(new TerrainJob(doc, id, "Thermal erosion", std::move(w)));
}

std::unique_ptr<TerrainJob> TerrainJob::hydraulic(const Document& doc, TerrainId id,
                                                  const terrain::HydraulicParams& p, Mask mask) {
  Work w = [p, mask](terrain::Terrain& t, const Progress* progress, int threads, TerrainJobOutcome& out) {
    terrain::UndoRecorder rec(t);
    terrain::ErosionReport r = terrain::erodeHydraulic(t.height, p, maskFor(t, mask), &rec, progress, threads);
    out.warnings = r.warnings;
    out.summary = erosionSummary("hydraulic erosion", r);
    out.erosion = r;
    return r.cancelled ? terrain::UndoStep{} : rec.finish("Hydraulic erosion");
  };
  return std::unique_ptr<TerrainJob>(new TerrainJob(doc, id, "Hydraulic erosion", std::move(w)));
}

std::unique_ptr<TerrainJob> TerrainJob::paintRules(const Document& doc, TerrainId id,
                                                   std::optional<std::vector<terrain::PaintRule>> rules) {
  std::vector<terrain::PaintRule> use;
  if (rules) {
    use = std::move(*rules);
  } else if (const TerrainAsset* t = doc.state().findTerrain(id)) {
    use = t->paintRules;
  }
  Work w = [use](terrain::Terrain& t, const Progress* progress, int threads, TerrainJobOutcome& out) {
    const auto t0 = std::chrono::steady_clock::now();
    terrain::PaintRulesResult r = terrain::applyPaintRules(t, use, {}, progress, threads);
    out.warnings = r.warnings;
    out.error = r.error;
    out.cancelled = r.cancelled;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.summary = "paint rules: " + std::to_string(use.size()) + " rules over " + std::to_string(r.changed.width()) +
                  " x " + std::to_string(r.changed.height()) + " samples in " + fmt("%.2f s", s);
    if (use.empty()) out.summary = "paint rules: the terrain has no rules; nothing painted";
    r.undo.setLabel("Paint rules");
    return std::move(r.undo);
  };
  return std::unique_ptr<TerrainJob>(new TerrainJob(doc, id, "Apply paint rules", std::move(w)));
}

std::unique_ptr<TerrainJob> TerrainJob::demInto(const Document& doc, TerrainId id, const std::string& path,
                                                terrain::DemImportOptions options) {
  Work w = [path, options](terrain::Terrain& t, const Progress* progress, int, TerrainJobOutcome& out) mutable {
    terrain::Heightfield& hf = t.height;
    options.samplesX = hf.samplesX();
    options.samplesY = hf.samplesY();
    terrain::DemImportResult r = terrain::importDem(path, options, progress);
    out.dem = r.report;
    out.warnings = r.report.warnings;
    out.cancelled = r.cancelled;
    if (!r.ok()) {
      out.error = r.error.empty() ? path + ": could not be imported" : r.error;
      return terrain::UndoStep{};
    }
    const glm::dvec2 demSize = r.report.groundSize, size = hf.sizeMetres();
    terrain::UndoRecorder rec(t);
    rec.recordHeights(hf.bounds());
    // Heights relative to the terrain's origin, which keeps its place.
    std::vector<float> v = r.heightfield->read(r.heightfield->bounds());
    const float dz = float(r.heightfield->origin().z - hf.origin().z);
    if (dz != 0.0f)
      for (float& h : v) h += dz;
    hf.write(hf.bounds(), v);
    out.summary = terrain::summary(r.report) +
                  fmt("; resampled onto the terrain's %.0f x %.0f m (horizontal scale %.3g x %.3g)", size.x, size.y,
                      demSize.x > 0 ? size.x / demSize.x : 0.0, demSize.y > 0 ? size.y / demSize.y : 0.0);
    return rec.finish("Import DEM into terrain");
  };
  return std::unique_ptr<TerrainJob>(new TerrainJob(doc, id, "Import DEM into terrain", std::move(w)));
}

}  // namespace hs::scene
