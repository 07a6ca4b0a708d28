#pragma once
// Long terrain edits (whole-terrain or masked erosion, paint rules, a DEM
// imported into an existing terrain) in three steps, so the editor can run
// the middle one on a worker thread with progress and Cancel, and the CLI
// runs all three in a row through the same code:
//
//   auto job = TerrainJob::thermal(doc, id, params);   // owning thread: copy-on-write snapshot
//   job->run(&progress);                                // any thread: works on the snapshot
//   TerrainJobOutcome o = job->commit(doc);             // owning thread: one undo step
//
// The live terrain is not touched until commit(), which moves the touched
// tiles in (terrain::UndoStep::adopt) and pushes a TerrainCommand. If the
// user changed any of those tiles meanwhile, commit() refuses (the result
// was computed from the old ones) and says so; nothing changes.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <QString>

#include "core/progress.h"
#include "scene/document.h"
#include "scene/terrain_edits.h"
#include "terrain/dem_import.h"
#include "terrain/erosion_hydraulic.h"
#include "terrain/erosion_thermal.h"
#include "terrain/paint_rules.h"

namespace hs::scene {

struct TerrainJobOutcome {
  bool ok = false;
  bool cancelled = false;              // nothing changed
  std::string error;                   // names the terrain (and file)
  std::string summary;                 // one line for Messages / stdout
  std::vector<std::string> warnings;
  terrain::Region changed;
  TerrainPushResult push;
  // Erosion: the solver's report (mass error, time step limits, timing).
  std::optional<terrain::ErosionReport> erosion;
  // DEM import: what the importer did (nodata fill, CRS, size).
  std::optional<terrain::DemImportReport> dem;
};

// Where erosion acts: the whole terrain, or weighted by a paint layer.
struct TerrainJobMask {
  int paintLayer = -1;  // -1: everywhere
};

class TerrainJob {
 public:
  using Mask = TerrainJobMask;

  static std::unique_ptr<TerrainJob> thermal(const Document& doc, TerrainId id, const terrain::ThermalParams& p,
                                             Mask mask = {});
  static std::unique_ptr<TerrainJob> hydraulic(const Document& doc, TerrainId id, const terrain::HydraulicParams& p,
                                               Mask mask = {});
  // The terrain's own rules (TerrainAsset::paintRules) unless `rules` is given.
  static std::unique_ptr<TerrainJob> paintRules(const Document& doc, TerrainId id,
                                                std::optional<std::vector<terrain::PaintRule>> rules = {});
  // The DEM (window, CRS mode and resampling from `options`) resampled onto
  // this terrain's grid: its heights replace the terrain's; the terrain
  // keeps its size in metres and origin (the DEM is stretched to fit; the
  // summary says by how much).
  static std::unique_ptr<TerrainJob> demInto(const Document& doc, TerrainId id, const std::string& path,
                                             terrain::DemImportOptions options);

  ~TerrainJob();
  // Null terrain, or another job already running on it.
  bool valid() const { return valid_; }
  const std::string& invalidReason() const { return error_; }
  const QString& label() const { return label_; }
  TerrainId terrain() const { return id_; }

  // The work, on any thread; `threads` 0 = all.
  void run(const Progress* progress, int threads = 0);
  // On the owning thread, after run().
  TerrainJobOutcome commit(Document& doc);

 private:
  using Work = std::function<terrain::UndoStep(terrain::Terrain& work, const Progress* progress, int threads,
                                               TerrainJobOutcome& out)>;
  TerrainJob(const Document& doc, TerrainId id, QString label, Work work);

  TerrainId id_;
  QString label_;
  Work work_;
  bool valid_ = false;
  std::string error_;
  std::string terrainName_;
  std::shared_ptr<TerrainData> live_;
  terrain::Terrain base_;    // the live terrain when the job started (shares tiles)
  terrain::Terrain result_;  // what the worker edits
  terrain::UndoStep step_;
  TerrainJobOutcome outcome_;
  bool ran_ = false;
};

}  // namespace hs::scene
