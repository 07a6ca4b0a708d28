#pragma once
// The Terrain panel's "Paint rules" group (Unreal's auto-material, Gaea's
// and World Machine's slope/height selectors): the terrain's rules in the
// order they apply (later rules cover earlier ones), each with its target
// layer, an altitude band and a slope band (each with a blend width), and a
// strength; adding, removing, reordering, enabling and editing them, each
// one undo step through the document (scene::ops::setTerrainPaintRules; a
// spin box stepped or scrubbed until it loses focus folds into one step).
// The chosen rule's effect is previewed on a coarse grid of the terrain's
// samples (terrain/paint_rule_preview.h). "Apply Paint Rules" paints them
// (the panel runs it on a worker with progress and Cancel).
#include <functional>
#include <vector>

#include <QGroupBox>

#include "scene/document.h"
#include "terrain/paint_rules.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QPushButton;
class QToolButton;

namespace hs::app {

class TerrainRulesEditor : public QGroupBox {
  Q_OBJECT
 public:
  // `terrain`: the terrain the panel works on (nullptr: none); `apply`: runs
  // the rules (the panel's job with progress and Cancel).
  TerrainRulesEditor(scene::Document& doc, std::function<const scene::TerrainAsset*()> terrain,
                     std::function<void()> apply, QWidget* parent);

  // Shows the terrain's rules and the chosen one again (after any change, undo included).
  void refresh();
  int currentRule() const;
  void setCurrentRule(int index);

  // --- commands (the buttons call them; tests drive them) -------------------
  // A new rule at the end (steep ground for the chosen layer); returns its index or -1.
  int addRule();
  bool removeRule(int index);
  // Moves a rule one place earlier (-1) or later (+1) in the order.
  bool moveRule(int index, int by);
  bool setRule(int index, const terrain::PaintRule& rule, const QString& mergeKey = {});
  // Replaces the rules with the defaults for this terrain's height range.
  bool resetToDefaults();
  // The chosen rule's preview: share of the terrain it reaches.
  double previewCoverage() const { return coverage_; }

 private:
  void build();
  void refreshForm();
  void refreshPreview();
  // Pushes the chosen rule with `change` applied.
  void editRule(const std::function<void(terrain::PaintRule&)>& change, const QString& mergeKey = {});
  QString scrubKey(const char* field) const;
  bool push(std::vector<terrain::PaintRule> rules, const QString& mergeKey = {});
  QString describe(const terrain::PaintRule& r, const std::vector<terrain::Material>& materials) const;

  scene::Document& doc_;
  std::function<const scene::TerrainAsset*()> terrain_;
  std::function<void()> apply_;
  bool updating_ = false;
  int scrub_ = 0;  // bumped when a spin box loses focus: the next edit is a new undo step
  double coverage_ = 0.0;
  std::vector<terrain::PaintRule> shownRules_;
  std::vector<std::string> shownLayers_;

  QListWidget* list_ = nullptr;
  QToolButton *add_ = nullptr, *remove_ = nullptr, *up_ = nullptr, *down_ = nullptr;
  QPushButton *defaults_ = nullptr, *applyButton_ = nullptr;
  QComboBox* layer_ = nullptr;
  QDoubleSpinBox* strength_ = nullptr;
  QCheckBox *useAltitude_ = nullptr, *useSlope_ = nullptr;
  QDoubleSpinBox *altMin_ = nullptr, *altMax_ = nullptr, *altBlend_ = nullptr;
  QDoubleSpinBox *slopeMin_ = nullptr, *slopeMax_ = nullptr, *slopeBlend_ = nullptr;
  QLabel *preview_ = nullptr, *coverageText_ = nullptr, *range_ = nullptr;
  QWidget* form_ = nullptr;
};

}  // namespace hs::app
