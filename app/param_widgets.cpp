#include "app/param_widgets.h"

#include <algorithm>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSpinBox>

namespace hs::app {
namespace {

QString suffixOf(const ParamDecl& p) {
  const QString symbol = QString::fromUtf8(unitSymbol(p.unit));
  if (symbol.isEmpty()) return {};
  return p.unit == Unit::Degrees ? symbol : " " + symbol;
}

double defaultOf(const ParamDecl& p, int component) {
  const Json& d = p.defaultValue;
  if (component >= 0 && d.is_array() && size_t(component) < d.size() && d[size_t(component)].is_number())
    return d[size_t(component)].get<double>();
  if (d.is_number()) return d.get<double>();
  return std::clamp(0.0, componentMin(p, std::max(component, 0)), componentMax(p, std::max(component, 0)));
}

}  // namespace

QString paramLabel(const ParamDecl& p) { return QString::fromStdString(p.label); }

void tagParamWidget(QWidget* w, const ParamDecl& p, int component) {
  w->setProperty(kParamProperty, QString::fromStdString(p.key));
  w->setProperty(kComponentProperty, component);
  w->setToolTip(QString::fromStdString(paramHelp(p)));
}

QSpinBox* paramIntSpin(const ParamDecl& p, QWidget* parent, int component) {
  auto* s = new QSpinBox(parent);
  const int i = std::max(component, 0);
  s->setRange(int(componentMin(p, i)), int(componentMax(p, i)));
  s->setSingleStep(std::max(1, int(p.step)));
  s->setSuffix(suffixOf(p));
  s->setValue(int(defaultOf(p, component)));
  s->setKeyboardTracking(false);
  tagParamWidget(s, p, component);
  return s;
}

QDoubleSpinBox* paramDoubleSpin(const ParamDecl& p, QWidget* parent, int component) {
  auto* s = new QDoubleSpinBox(parent);
  const int i = std::max(component, 0);
  // Decimals first: setDecimals rounds the range to them.
  s->setDecimals(p.decimals);
  s->setRange(componentMin(p, i), componentMax(p, i));
  s->setSingleStep(p.step);
  s->setSuffix(suffixOf(p));
  s->setValue(defaultOf(p, component));
  s->setKeyboardTracking(false);
  tagParamWidget(s, p, component);
  return s;
}

QComboBox* paramCombo(const ParamDecl& p, QWidget* parent, const QStringList& labels) {
  auto* c = new QComboBox(parent);
  for (size_t i = 0; i < p.choices.size(); ++i) {
    const QString name = QString::fromStdString(p.choices[i].substr(0, p.choices[i].find('|')));
    c->addItem(int(i) < labels.size() ? labels[int(i)] : name, name);
  }
  if (p.defaultValue.is_string())
    c->setCurrentIndex(std::max(0, c->findData(QString::fromStdString(p.defaultValue.get<std::string>()))));
  tagParamWidget(c, p);
  return c;
}

FieldSpec paramFieldSpec(const ParamDecl& p, const std::string& path) {
  FieldSpec spec;
  spec.path = path;
  spec.type = scene::FieldType::Double;
  spec.min = p.min;
  spec.max = p.max;
  spec.step = p.step;
  spec.unit = unitSymbol(p.unit);
  return spec;
}

}  // namespace hs::app
