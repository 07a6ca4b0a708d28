#pragma once
// The viewport's stereo preview settings: off (the free editor view), or the
// active camera's left eye, right eye, side by side, or red/cyan anaglyph,
// framed at the export's eye aspect; the comfort budget the readout checks.
// The active camera is the selected camera, else the shot camera (the one
// an export uses by default). The viewport draws through
// render::StereoPreviewRenderer; ComfortReadout shows the frame's nearest
// and farthest parallax, red when outside the budget.
#include <QLabel>
#include <QObject>
#include <optional>

#include "scene/scene_state.h"
#include "sequencer/camera_cuts.h"
#include "sequencer/comfort_check.h"

namespace hs::app {

class Selection;

enum class StereoPreviewMode { Off, Left, Right, SideBySide, Anaglyph };

class StereoPreviewSettings : public QObject {
  Q_OBJECT
 public:
  explicit StereoPreviewSettings(QObject* parent = nullptr);

  StereoPreviewMode mode() const { return mode_; }
  const sequencer::ComfortBudget& budget() const { return budget_; }
  double outputAspect() const { return aspect_; }
  // The camera the preview looks through: the selected camera, else the
  // camera cuts' at the state's frame (a transition: its stronger shot),
  // else the shot camera.
  scene::EntityId activeCamera(const scene::SceneState& state, const Selection& selection) const;
  // With no camera selected, the camera cuts' shot at the state's frame,
  // if a cut covers it and its cameras exist (automatic exposure adapts
  // from the shot's start, as the export's).
  std::optional<sequencer::Shot> activeShot(const scene::SceneState& state, const Selection& selection) const;
  // The same shot if a transition is running there: the preview then shows
  // both shots combined, as the export does.
  std::optional<sequencer::Shot> activeTransition(const scene::SceneState& state, const Selection& selection) const;
  static QString modeName(StereoPreviewMode m);

 public slots:
  void setMode(hs::app::StereoPreviewMode mode);
  void setBudget(const sequencer::ComfortBudget& budget);
  // The export's eye size (the Export dialog sets it; remembered).
  void setOutputSize(int width, int height);

 signals:
  void changed();

 private:
  StereoPreviewMode mode_ = StereoPreviewMode::Off;
  sequencer::ComfortBudget budget_;
  double aspect_ = 16.0 / 9.0;
};

// The comfort readout in the viewport's corner.
class ComfortReadout : public QLabel {
  Q_OBJECT
 public:
  explicit ComfortReadout(QWidget* parent = nullptr);
  void showResult(const sequencer::ComfortResult& result, const sequencer::ComfortBudget& budget, bool stereo);
  bool outsideBudget() const { return outside_; }

 private:
  bool outside_ = false;
};

// "-0.45%"
QString formatParallax(double share);

}  // namespace hs::app
