#pragma once
// The editor's fields made from parameter declarations (core/params.h), so a
// dialog or panel that runs an operation the CLI shares takes its ranges,
// default, unit, label and tooltip from the one declaration: the two
// frontends differ in presentation only. Every widget made here carries the
// parameter's key (and the number's index in a tuple) as properties
// (kParamProperty, kComponentProperty), which tests/app/test_editor_params
// uses to check each field against its declaration. Object names are the
// caller's (tests find fields by them).
#include <QString>
#include <QStringList>

#include "app/field_editors.h"
#include "core/params.h"

class QAbstractSpinBox;
class QComboBox;
class QDoubleSpinBox;
class QSpinBox;
class QWidget;

namespace hs::app {

inline constexpr const char* kParamProperty = "hsParam";
inline constexpr const char* kComponentProperty = "hsParamComponent";

// The form label: the declaration's label.
QString paramLabel(const ParamDecl& p);

// A number field for `p` (number `component` of a tuple; -1 for a scalar):
// a QSpinBox for whole numbers, else a QDoubleSpinBox, with the declared
// range, decimals, step, unit suffix, default and help as tooltip; keyboard
// tracking off (a typed value counts when committed).
QSpinBox* paramIntSpin(const ParamDecl& p, QWidget* parent, int component = -1);
QDoubleSpinBox* paramDoubleSpin(const ParamDecl& p, QWidget* parent, int component = -1);
// The choices of `p` (item data: the choice's name; `labels`, if given,
// the texts shown in the same order), the default selected.
QComboBox* paramCombo(const ParamDecl& p, QWidget* parent, const QStringList& labels = {});
// A FieldEditor spec for panels built from field editors (the Camera Path
// panel): the declared range, step and unit, `path` as the object name.
FieldSpec paramFieldSpec(const ParamDecl& p, const std::string& path);
// Marks `w` (a FieldEditor's number box, a widget made elsewhere) as the
// field of `p`'s number `component`.
void tagParamWidget(QWidget* w, const ParamDecl& p, int component = -1);

}  // namespace hs::app
