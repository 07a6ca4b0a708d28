#pragma once
// The Scene Settings dock: sky, lighting, exposure, grid, anti-aliasing,
// the tone map and post-processing, depth of field and transparency (with the last frame's OIT figures),
// generated from scene::settingsFields(); edits go through
// scene::ops::setSettingsField (undoable, one step per gesture).
#include <map>
#include <string>
#include <vector>

#include <QWidget>

#include "scene/document.h"
#include "scene/fields.h"

class QLabel;

namespace hs::render {
struct OitStats;
}

namespace hs::app {

class FieldEditor;
class KeyButton;
class Keying;
class TimelineClock;

class SettingsPanel : public QWidget {
  Q_OBJECT
 public:
  explicit SettingsPanel(scene::Document& doc, QWidget* parent = nullptr);
  FieldEditor* editorFor(const std::string& key) const;
  // Key buttons beside each animatable field, values shown at the
  // timeline's frame, and edits of animated fields keyed in the same undo
  // step, as the Properties dock does for entities (scene/object_tracks.h).
  void enableKeying(Keying& keying, TimelineClock& clock);
  // The key button of field `key` ("fog_density"); null before enableKeying.
  KeyButton* keyButtonFor(const std::string& key) const;
  // The last frame's transparency figures under the Transparency block
  // (mode, OIT memory, fragments per pixel, overflow: app/status_bar.h's
  // oitSummary); MainWindow passes every rendered frame's.
  void showTransparencyStats(const render::OitStats& stats);

 private:
  void refresh();
  const scene::SceneState& shown() const;

  scene::Document& doc_;
  std::vector<std::pair<const scene::SettingsField*, FieldEditor*>> rows_;
  std::map<std::string, FieldEditor*> byKey_;
  std::map<std::string, QWidget*> rowOf_;  // the editor's row, where a key button goes
  std::map<std::string, KeyButton*> keyButtons_;
  QLabel* oitStats_ = nullptr;
  Keying* keying_ = nullptr;
  TimelineClock* clock_ = nullptr;
  int editCounter_ = 0;
};

}  // namespace hs::app
