#pragma once
// A form of fields made from parameter declarations (param_widgets.h), one
// row per parameter, for dialogs that gather an operation's values: numbers
// (a field per number of a tuple), choices, flags and texts (a text may be
// a list of names instead, such as the scene's mesh assets). values() gives
// them as the JSON object keyed by declaration that the operations' helpers
// read (foliage::typeFromValues, scatterRules, plantFromValues), so a
// dialog needs no code per field.
//
// A row may be optional (a scatter's override of a type's rule): a check
// box before it enables it, and values() leaves it out while unchecked.
#include <map>
#include <string>
#include <vector>

#include <QStringList>
#include <QWidget>

#include "core/params.h"

class QCheckBox;
class QFormLayout;

namespace hs::app {

class ParamForm : public QWidget {
  Q_OBJECT
 public:
  // Text parameters listed in `names` become a list of those names ("" is
  // shown as "(none)"). Rows whose keys are in `optional` get a check box
  // (labelled with the declaration's label) in front: unchecked, their
  // fields are disabled and values() leaves them out.
  using TextChoices = std::map<std::string, QStringList>;
  ParamForm(const std::vector<ParamDecl>& params, QWidget* parent, const TextChoices& names = {},
            const std::vector<std::string>& optional = {});

  // Every row's value (optional rows only when checked), keyed by declaration.
  Json values() const;
  // Sets a row's fields (a number, a tuple as an array, a choice's or a
  // text's name, a bool). A name a list lacks is added to it.
  void setValue(const std::string& key, const Json& value);
  void setChecked(const std::string& key, bool checked);  // optional rows
  bool isChecked(const std::string& key) const;           // true for rows that are not optional
  // Greys a whole row out (check box included); values() leaves it out.
  void setRowEnabled(const std::string& key, bool enabled);
  // The field of number `component` of a tuple (-1: a scalar, a choice, a
  // flag, a text); nullptr when the form has no such row.
  QWidget* field(const std::string& key, int component = -1) const;

 signals:
  void edited();

 private:
  struct Row {
    ParamDecl decl;
    std::vector<QWidget*> fields;  // one per number of a tuple; else one
    QCheckBox* enable = nullptr;   // optional rows only
    bool rowEnabled = true;
  };
  bool included(const Row& r) const;
  void updateEnabled(Row& r);
  Row* find(const std::string& key);
  const Row* find(const std::string& key) const;

  QFormLayout* form_;
  std::vector<Row> rows_;
};

}  // namespace hs::app
