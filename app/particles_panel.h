#pragma once
// The Particles panel (a dock tab beside Foliage): the scene's emitters
// (name, sprite and blend, live particles at the playhead), Add Preset (a
// dialog made from `particles add`'s declaration, placed at the view's pivot
// unless a position is given), Remove, and the current emitter's fields: a
// form made from emitterParamDecls() (particles/emitter.h) and its keyed
// lists (rate and wind keys, bursts, size and colour over life) as JSON,
// each also drawn and dragged (the over-life curves, and the lists over
// scene time against the playback range and the playhead). Every
// change goes through scene/particle_ops.h, as `hybridscape-cli set EMITTER
// particles.FIELD` does: one undo step (a spin box's drag merges into one),
// refused values named in Messages with emitter and field, the document
// untouched. The viewport shows the particles at the playhead while
// scrubbing (the renderer evaluates them at the frame's time).
//
// Commands without dialogs (addPreset, setValue) serve the dialogs and tests.
#include <QDialog>
#include <QWidget>

#include <glm/vec3.hpp>

#include "core/json.h"
#include "scene/document.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTreeWidget;

namespace hs::app {

class MainWindow;
class ParamForm;

// `particles add`'s declaration as a form; the optional values (name,
// position, area, rate) apply only when checked.
class ParticlesAddDialog : public QDialog {
  Q_OBJECT
 public:
  ParticlesAddDialog(QWidget* parent, const glm::dvec3& pivot);
  Json values() const;

 private:
  ParamForm* form_;
};

class ParticlesPanel : public QWidget {
  Q_OBJECT
 public:
  explicit ParticlesPanel(MainWindow& window);

  // The timeline's clock, once it exists: the live counts follow its playhead.
  void followClock(class TimelineClock* clock);
  // Adds the Particles menu's commands to `menu`.
  void populateMenu(class QMenu* menu);

  // The emitter whose fields the form shows (kNoEntity: none).
  scene::EntityId currentEmitter() const { return current_; }
  void setCurrentEmitter(scene::EntityId id);

  // --- commands without dialogs ---------------------------------------------
  // `particles add`'s values keyed by declaration (preset, and optionally
  // name, at, area, rate, seed); without "at" or "area", at the view's pivot.
  // The new top entity, or kNoEntity (reported in Messages).
  scene::EntityId addPreset(const Json& values);
  // One field or list of an emitter; false (reported) if refused.
  // `merge`: successive values of the field merge into one undo step (a
  // spin box's drag); a curve's gesture is a step of its own.
  bool setValue(scene::EntityId id, const std::string& key, const Json& value, bool merge = true);
  // Keys the current emitter's `property` at the playhead with its value in
  // the form: "particles.rate_per_s" and "particles.wind_m_per_s" as keys
  // of the emitter's rate_keys and wind_keys (scene::ops::keyEmitterField),
  // a spawn value ("particles.size_m") on the timeline. false (reported)
  // if refused.
  bool keyAtPlayhead(const std::string& property);

  // --- with its dialog --------------------------------------------------------
  void requestAddPreset();

 private:
  void buildUi();
  void refresh();        // the list and the form
  void refreshCounts();  // live particles at the playhead
  void refreshForm();
  void refreshTimeKeys();  // the time curves' span and playhead
  void formEdited();
  void listEdited(const std::string& key, QLineEdit* edit);
  double playheadSeconds() const;
  void showProblem(const std::string& error);  // in Messages and in red under the list

  MainWindow& window_;
  scene::Document& doc_;
  scene::EntityId current_ = scene::kNoEntity;
  bool updating_ = false;

  QLabel *info_ = nullptr, *error_ = nullptr;
  QTreeWidget* list_ = nullptr;
  QPushButton* remove_ = nullptr;
  QComboBox* keyField_ = nullptr;
  QWidget* fields_ = nullptr;
  ParamForm* form_ = nullptr;
  std::vector<std::pair<std::string, QLineEdit*>> lists_;
  std::vector<std::pair<std::string, class LifeCurveEditor*>> curves_;  // size and colour over life
  std::vector<std::pair<std::string, class TimeKeysEditor*>> timeKeys_;  // rate and wind keys, bursts
  Json shown_;  // the form's values as refreshForm() left them
};

}  // namespace hs::app
