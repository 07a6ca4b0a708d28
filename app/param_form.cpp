#include "app/param_form.h"

#include <algorithm>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>

#include "app/param_widgets.h"

namespace hs::app {
namespace {

QString noneText(const QString& name) { return name.isEmpty() ? QString("(none)") : name; }

double numberOf(QWidget* w) {
  if (auto* i = qobject_cast<QSpinBox*>(w)) return i->value();
  if (auto* d = qobject_cast<QDoubleSpinBox*>(w)) return d->value();
  return 0.0;
}

void setNumber(QWidget* w, double v) {
  if (auto* i = qobject_cast<QSpinBox*>(w)) i->setValue(int(v));
  else if (auto* d = qobject_cast<QDoubleSpinBox*>(w)) d->setValue(v);
}

// A number as the declaration's type: whole numbers as JSON integers (the
// helpers and checkParam read them as such).
Json numberJson(const ParamDecl& p, double v) { return p.integer ? Json(static_cast<long long>(v)) : Json(v); }

}  // namespace

ParamForm::ParamForm(const std::vector<ParamDecl>& params, QWidget* parent, const TextChoices& names,
                     const std::vector<std::string>& optional)
    : QWidget(parent), form_(new QFormLayout(this)) {
  form_->setContentsMargins(0, 0, 0, 0);
  rows_.reserve(params.size());
  for (const ParamDecl& p : params) {
    Row row;
    row.decl = p;
    QWidget* shown = nullptr;  // what the form row holds
    switch (p.type) {
      case ParamType::Number: {
        auto* box = new QWidget(this);
        auto* h = new QHBoxLayout(box);
        h->setContentsMargins(0, 0, 0, 0);
        for (int c = 0; c < p.count; ++c) {
          const int component = p.count == 1 ? -1 : c;
          QAbstractSpinBox* s = p.integer ? static_cast<QAbstractSpinBox*>(paramIntSpin(p, box, component))
                                          : static_cast<QAbstractSpinBox*>(paramDoubleSpin(p, box, component));
          if (auto* i = qobject_cast<QSpinBox*>(s)) connect(i, &QSpinBox::valueChanged, this, &ParamForm::edited);
          if (auto* d = qobject_cast<QDoubleSpinBox*>(s))
            connect(d, &QDoubleSpinBox::valueChanged, this, &ParamForm::edited);
          if (c > 0) h->addWidget(new QLabel(p.ordered && p.count == 2 ? "to" : QString(QChar::fromLatin1(p.separator)), box));
          h->addWidget(s, 1);
          row.fields.push_back(s);
        }
        shown = box;
        break;
      }
      case ParamType::Choice: {
        QComboBox* c = paramCombo(p, this);
        connect(c, &QComboBox::currentIndexChanged, this, &ParamForm::edited);
        row.fields.push_back(c);
        shown = c;
        break;
      }
      case ParamType::Flag: {
        auto* c = new QCheckBox(this);
        c->setChecked(p.defaultValue.is_boolean() && p.defaultValue.get<bool>());
        tagParamWidget(c, p);
        connect(c, &QCheckBox::toggled, this, &ParamForm::edited);
        row.fields.push_back(c);
        shown = c;
        break;
      }
      case ParamType::Text: {
        const QString initial =
            p.defaultValue.is_string() ? QString::fromStdString(p.defaultValue.get<std::string>()) : QString();
        if (auto it = names.find(p.key); it != names.end()) {
          auto* c = new QComboBox(this);
          for (const QString& n : it->second) c->addItem(noneText(n), n);
          c->setCurrentIndex(std::max(0, c->findData(initial)));
          tagParamWidget(c, p);
          connect(c, &QComboBox::currentIndexChanged, this, &ParamForm::edited);
          row.fields.push_back(c);
          shown = c;
        } else {
          auto* e = new QLineEdit(initial, this);
          tagParamWidget(e, p);
          connect(e, &QLineEdit::textEdited, this, &ParamForm::edited);
          row.fields.push_back(e);
          shown = e;
        }
        break;
      }
    }
    const QString label = paramLabel(p);
    if (std::find(optional.begin(), optional.end(), p.key) != optional.end()) {
      row.enable = new QCheckBox(label, this);
      row.enable->setToolTip("Use this value for this run only (unchecked: the type's own)");
      form_->addRow(row.enable, shown);
    } else {
      form_->addRow(label, shown);
    }
    rows_.push_back(std::move(row));
  }
  // After the rows exist: the pointers into rows_ stay put from here on.
  for (Row& r : rows_) {
    if (r.enable) {
      connect(r.enable, &QCheckBox::toggled, this, [this, key = r.decl.key] {
        updateEnabled(*find(key));
        emit edited();
      });
    }
    updateEnabled(r);
  }
}

ParamForm::Row* ParamForm::find(const std::string& key) {
  for (Row& r : rows_)
    if (r.decl.key == key) return &r;
  return nullptr;
}

const ParamForm::Row* ParamForm::find(const std::string& key) const {
  for (const Row& r : rows_)
    if (r.decl.key == key) return &r;
  return nullptr;
}

bool ParamForm::included(const Row& r) const { return r.rowEnabled && (!r.enable || r.enable->isChecked()); }

void ParamForm::updateEnabled(Row& r) {
  if (r.enable) r.enable->setEnabled(r.rowEnabled);
  for (QWidget* f : r.fields) f->setEnabled(included(r));
}

Json ParamForm::values() const {
  Json out = Json::object();
  for (const Row& r : rows_) {
    if (!included(r)) continue;
    const ParamDecl& p = r.decl;
    switch (p.type) {
      case ParamType::Number:
        if (p.count == 1) {
          out[p.key] = numberJson(p, numberOf(r.fields[0]));
        } else {
          Json a = Json::array();
          for (QWidget* f : r.fields) a.push_back(numberJson(p, numberOf(f)));
          out[p.key] = a;
        }
        break;
      case ParamType::Choice:
      case ParamType::Text:
        if (auto* c = qobject_cast<QComboBox*>(r.fields[0])) out[p.key] = c->currentData().toString().toStdString();
        else out[p.key] = static_cast<QLineEdit*>(r.fields[0])->text().trimmed().toStdString();
        break;
      case ParamType::Flag: out[p.key] = static_cast<QCheckBox*>(r.fields[0])->isChecked(); break;
    }
  }
  return out;
}

void ParamForm::setValue(const std::string& key, const Json& value) {
  Row* r = find(key);
  if (!r) return;
  if (r->decl.type == ParamType::Number) {
    if (value.is_array()) {
      for (size_t c = 0; c < r->fields.size() && c < value.size(); ++c)
        if (value[c].is_number()) setNumber(r->fields[c], value[c].get<double>());
    } else if (value.is_number() && !r->fields.empty()) {
      setNumber(r->fields[0], value.get<double>());
    }
  } else if (r->decl.type == ParamType::Flag) {
    if (value.is_boolean()) static_cast<QCheckBox*>(r->fields[0])->setChecked(value.get<bool>());
  } else if (value.is_string()) {
    const QString name = QString::fromStdString(value.get<std::string>());
    if (auto* c = qobject_cast<QComboBox*>(r->fields[0])) {
      int i = c->findData(name);
      if (i < 0 && r->decl.type == ParamType::Text) {
        // A name no longer listed (a renamed asset): kept, not replaced.
        c->addItem(noneText(name), name);
        i = c->count() - 1;
      }
      if (i >= 0) c->setCurrentIndex(i);
    } else {
      static_cast<QLineEdit*>(r->fields[0])->setText(name);
    }
  }
}

void ParamForm::setChecked(const std::string& key, bool checked) {
  if (Row* r = find(key); r && r->enable) r->enable->setChecked(checked);
}

bool ParamForm::isChecked(const std::string& key) const {
  const Row* r = find(key);
  return r && (!r->enable || r->enable->isChecked());
}

void ParamForm::setRowEnabled(const std::string& key, bool enabled) {
  Row* r = find(key);
  if (!r) return;
  r->rowEnabled = enabled;
  updateEnabled(*r);
}

QWidget* ParamForm::field(const std::string& key, int component) const {
  const Row* r = find(key);
  if (!r) return nullptr;
  const size_t i = size_t(std::max(component, 0));
  return i < r->fields.size() ? r->fields[i] : nullptr;
}

}  // namespace hs::app
