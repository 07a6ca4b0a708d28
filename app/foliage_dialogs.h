#pragma once
// The Foliage panel's dialogs. Their fields are the shared operations'
// declared parameters (foliage/foliage_operations.h) through ParamForm, so
// ranges, defaults, units and tooltips are those of `hybridscape-cli
// foliage ...`: New/Edit Type (`foliage type add`), Generate Plant
// (`foliage plant`), Scatter (`foliage scatter`). Each gathers and checks
// values; the panel runs the operation.
#include <string>
#include <vector>

#include <QDialog>

#include "foliage/foliage_type.h"
#include "foliage/plants.h"
#include "foliage/tools.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QTimer;

namespace hs::app {

class PreviewRenderer;

class ParamForm;

// Every parameter of `foliage type add` the editor shows (the mesh a list
// of the scene's mesh assets, the paint layer a list of the terrain's
// layers), and the name. OK checks the type (foliage::typeFromValues: the
// same checks as the CLI) and stays open with the message when it fails.
class FoliageTypeDialog : public QDialog {
  Q_OBJECT
 public:
  // `initial`: the type to edit (nullptr: a new one named `suggestedName`).
  FoliageTypeDialog(QWidget* parent, const QStringList& meshes, const QStringList& layers,
                    const foliage::FoliageType* initial = nullptr, const QString& suggestedName = "Foliage");
  // The type the fields describe; false with `error` naming the field.
  bool type(foliage::FoliageType& out, std::string& error) const;
  ParamForm* form() const { return form_; }
  QLineEdit* nameField() const { return name_; }

  void accept() override;

 private:
  QLineEdit* name_;
  ParamForm* form_;
  QLabel* error_;
};

// `foliage plant`'s parameters and the asset's name. Choosing a kind puts
// that kind's defaults in the fields (a grass clump is not 12 m tall).
class PlantDialog : public QDialog {
  Q_OBJECT
 public:
  PlantDialog(QWidget* parent, const QString& suggestedName);
  QString name() const;
  foliage::PlantParams params() const;
  ParamForm* form() const { return form_; }
  QLineEdit* nameField() const { return name_; }
  // The live preview: the plant the fields grow now (drawn on a worker a
  // moment after the last edit), or what the generator said.
  QLabel* preview() const { return preview_; }
  int previewsShown() const { return previewsShown_; }  // images received (tests)

 private:
  void showKindDefaults();
  void requestPreview();
  QLineEdit* name_;
  ParamForm* form_;
  QLabel* preview_ = nullptr;
  PreviewRenderer* renderer_ = nullptr;
  QTimer* previewDelay_ = nullptr;
  int previewsShown_ = 0;
};

// `foliage scatter`'s options for one type (its rules may be overridden
// for this scatter: each override has a check box and starts at the type's
// value) or for every type competing for room in list order (the types'
// own rules), with the seed and an optional region.
class FoliageScatterDialog : public QDialog {
  Q_OBJECT
 public:
  // `selected`: the type chosen first (-1: all types).
  FoliageScatterDialog(QWidget* parent, const std::vector<foliage::FoliageType>& types, int selected,
                       const QStringList& layers);
  // The types to scatter: one, or all of them in order.
  foliage::TypeSet types() const;
  // The checked options keyed by declaration (what the CLI's parser gives).
  Json values() const;
  ParamForm* form() const { return form_; }
  QComboBox* typeField() const { return which_; }

 private:
  void showTypeRules();
  std::vector<foliage::FoliageType> types_;
  QComboBox* which_;
  ParamForm* form_;
};

// `foliage fill`'s options: the type (one of the list), the terrain's
// paint layer, the minimum weight, the seed and an optional region.
class FoliageFillDialog : public QDialog {
  Q_OBJECT
 public:
  FoliageFillDialog(QWidget* parent, const std::vector<foliage::FoliageType>& types, int selected,
                    const QStringList& layers);
  foliage::TypeSet types() const;
  Json values() const;
  ParamForm* form() const { return form_; }

 private:
  QComboBox* which_;
  ParamForm* form_;
};

// Move Selected Instances By…: `foliage move`'s offset and keep-height
// (its region is the selection), declared once (foliage_operations.h).
class FoliageMoveDialog : public QDialog {
  Q_OBJECT
 public:
  FoliageMoveDialog(QWidget* parent, size_t selected);
  Json values() const;
  ParamForm* form() const { return form_; }

 private:
  ParamForm* form_;
};

}  // namespace hs::app
