#pragma once
// A brush stroke: the pen moves, dabs land every `spacing * radius` metres
// along its path (pressure interpolated between pen samples), and each dab
// reports the region it changed (for the renderer: upload only that). The
// first time a dab touches a tile the stroke copies the tile (before-copy);
// finish() hands those copies over as one UndoStep, so a stroke is one undo
// step that holds only the tiles it touched.
#include <string>
#include <vector>

#include "terrain/brush.h"
#include "terrain/brush_dab.h"
#include "terrain/region.h"
#include "terrain/terrain.h"
#include "terrain/undo_step.h"

namespace hs::terrain {

struct StrokeUpdate {
  int dabs = 0;
  Region changed;            // union of the dabs' regions in this call
  size_t changedBytes = 0;   // bytes a renderer uploads for `changed` (heights: 4/sample; paint: 2/sample/layer)
  double erosionMassError = 0.0;  // erosion brushes: summed |mass error| of the dabs, m^3
};

class Stroke {
 public:
  // `threads`: 0 = all available threads (dabs over ~32 rows are split).
  Stroke(Terrain& terrain, const BrushSettings& settings, int threads = 0);

  // Pen at `local` (metres from the terrain origin) with `pressure` in [0,1].
  // The first call places one dab; later calls place dabs along the segment
  // from the previous position, `spacing` apart, carrying the remainder over.
  StrokeUpdate moveTo(const glm::dvec2& local, float pressure = 1.0f);
  // One dab exactly here, regardless of spacing (tests, benchmarks, clicks).
  StrokeUpdate dabAt(const glm::dvec2& local, float pressure = 1.0f);

  // Ends the stroke: one undo step with the before-copies of the touched
  // tiles, labelled with the tool name. The stroke cannot be used afterwards.
  UndoStep finish();

  Region changed() const { return total_; }
  size_t undoBytes() const { return recorder_.bytes(); }
  const BrushSettings& settings() const { return settings_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  int dabCount() const { return dabs_; }

 private:
  Region applyDab(const glm::dvec2& local, float pressure, double* massError);
  size_t bytesFor(const Region& r) const;

  Terrain& terrain_;
  BrushSettings settings_;
  FalloffTable falloff_;
  UndoRecorder recorder_;
  std::vector<std::string> warnings_;
  int threads_;
  bool started_ = false, finished_ = false;
  glm::dvec2 last_{0.0};
  float lastPressure_ = 1.0f;
  double carried_ = 0.0;  // distance since the last dab
  int dabs_ = 0;
  Region total_;
  bool targetPicked_ = false;
  FlattenTarget flatten_;
};

// Ramp: a straight slope from a to b (x, y local metres; z local height),
// `width` metres wide, with `falloff` of the half-width blending into the
// ground at the sides and `strength` (0..1) of the way there. Along the
// centreline the result is exactly linear in the distance from a.
struct RampSettings {
  glm::dvec3 a{0.0}, b{0.0};
  double width = 10.0;
  float falloff = 0.3f;
  float strength = 1.0f;
};
struct RampResult {
  Region changed;
  UndoStep undo;
  std::vector<std::string> warnings;
  std::string error;
  bool ok() const { return error.empty(); }
};
RampResult applyRamp(Terrain& terrain, const RampSettings& settings, int threads = 0);

}  // namespace hs::terrain
