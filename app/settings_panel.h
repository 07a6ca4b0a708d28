#pragma once
// The Scene Settings dock (sky, lighting, exposure, grid, anti-aliasing,
// fog, depth of field and transparency, with the last frame's OIT
// figures) and the Post dock (the post chain in its order: the tone map,
// then every settings.post.* effect with its enable box and parameters,
// the stored LUT): two panels generated from scene::settingsFields(),
// split by key (inPostPanel). Edits go through scene::ops::setSettingsField
// (undoable, one step per gesture).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <QWidget>

#include "scene/document.h"
#include "scene/fields.h"

class QFormLayout;
class QLabel;
class QPushButton;

namespace hs::render {
struct OitStats;
}

namespace hs::app {

class FieldEditor;
class KeyButton;
class Keying;
class Prompts;
class TimelineClock;

enum class SettingsSection { Scene, Post };

class SettingsPanel : public QWidget {
  Q_OBJECT
 public:
  // `section`: which fields it shows (objectName "settingsPanel" or "postPanel").
  explicit SettingsPanel(scene::Document& doc, QWidget* parent = nullptr,
                         SettingsSection section = SettingsSection::Scene);
  // Whether settings field `key` belongs to the Post dock.
  static bool inPostPanel(const std::string& key);
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
  // Where Import LUT... asks for its file and reports a file it refuses
  // (MainWindow's prompts, which tests answer).
  void setPrompts(std::function<Prompts&()> prompts) { prompts_ = std::move(prompts); }
  // Import LUT...'s work: reads `path` (scene/color_lut.h) and grades the
  // scene with it as one undo step; a refused file is shown as an error
  // naming it and the scene is left as it was. False if refused.
  bool importLut(const QString& path);
  // Import OCIO config...'s work: reads the config at `path` with the LUTs
  // under its search paths (scene/ocio_config.h) and views the scene
  // through its default display and view as one undo step; a refused
  // config is shown as an error naming it. False if refused.
  bool importOcioConfig(const QString& path);

 private:
  void refresh();
  void addLutRow(QWidget* content, QFormLayout* form);
  void addOcioRow(QWidget* content, QFormLayout* form);
  void refreshOcioChoices();
  const scene::SceneState& shown() const;

  scene::Document& doc_;
  std::vector<std::pair<const scene::SettingsField*, FieldEditor*>> rows_;
  std::map<std::string, FieldEditor*> byKey_;
  std::map<std::string, QWidget*> rowOf_;  // the editor's row, where a key button goes
  std::map<std::string, KeyButton*> keyButtons_;
  QLabel* oitStats_ = nullptr;
  QLabel* lutName_ = nullptr;      // the stored LUT's file name, or "none"
  QPushButton* lutRemove_ = nullptr;
  QLabel* ocioName_ = nullptr;     // the stored OpenColorIO config's name, or "none"
  QPushButton* ocioRemove_ = nullptr;
  std::function<Prompts&()> prompts_;
  Keying* keying_ = nullptr;
  TimelineClock* clock_ = nullptr;
  int editCounter_ = 0;
};

}  // namespace hs::app
