#include "app/form_widgets.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QScrollArea>
#include <QToolButton>
#include <QVBoxLayout>

namespace hs::app {

QDoubleSpinBox* numberSpin(QWidget* parent, double min, double max, double step, int decimals, const QString& suffix,
                           const QString& tip) {
  auto* s = new QDoubleSpinBox(parent);
  s->setRange(min, max);
  s->setSingleStep(step);
  s->setDecimals(decimals);
  s->setSuffix(suffix);
  s->setToolTip(tip);
  s->setKeyboardTracking(false);
  return s;
}

QWidget* editorRow(QWidget* parent, QWidget* editor) {
  auto* row = new QWidget(parent);
  auto* h = new QHBoxLayout(row);
  h->setContentsMargins(0, 0, 0, 0);
  h->setSpacing(2);
  h->addWidget(editor, 1);
  return row;
}

void putInScrollArea(QWidget* panel, QWidget* content, bool horizontalScroll) {
  auto* outer = new QVBoxLayout(panel);
  outer->setContentsMargins(0, 0, 0, 0);
  auto* scroll = new QScrollArea(panel);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  if (!horizontalScroll) scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll->setWidget(content);
  outer->addWidget(scroll);
}

QToolButton* namedToolButton(QWidget* parent, const QString& text, const char* name, const QString& tip) {
  auto* b = new QToolButton(parent);
  b->setText(text);
  b->setObjectName(name);
  b->setToolTip(tip);
  return b;
}

}  // namespace hs::app
