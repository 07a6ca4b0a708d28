#include "app/message_panel.h"

#include <QApplication>
#include <QClipboard>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QStyle>
#include <QTime>
#include <QToolButton>
#include <QTreeWidget>
#include <QVBoxLayout>

namespace hs::app {
namespace {

constexpr int kLevelRole = Qt::UserRole + 1;
constexpr int kMaxMessages = 5000;

QIcon levelIcon(const QWidget* w, MessageLevel level) {
  switch (level) {
    case MessageLevel::Info: return w->style()->standardIcon(QStyle::SP_MessageBoxInformation);
    case MessageLevel::Warning: return w->style()->standardIcon(QStyle::SP_MessageBoxWarning);
    case MessageLevel::Error: return w->style()->standardIcon(QStyle::SP_MessageBoxCritical);
  }
  return {};
}

}  // namespace

MessagePanel::MessagePanel(QWidget* parent) : QWidget(parent) {
  setObjectName("messagePanel");
  auto* v = new QVBoxLayout(this);
  v->setContentsMargins(0, 0, 0, 0);
  v->setSpacing(0);
  auto* bar = new QHBoxLayout;
  bar->setContentsMargins(4, 2, 4, 2);
  const char* names[3] = {"Info", "Warnings", "Errors"};
  for (int i = 0; i < 3; ++i) {
    filters_[i] = new QToolButton(this);
    filters_[i]->setCheckable(true);
    filters_[i]->setChecked(true);
    filters_[i]->setAutoRaise(true);
    filters_[i]->setIcon(levelIcon(this, MessageLevel(i)));
    filters_[i]->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    filters_[i]->setText(QString("0 %1").arg(names[i]));
    filters_[i]->setToolTip(QString("Show %1").arg(QString(names[i]).toLower()));
    connect(filters_[i], &QToolButton::toggled, this, &MessagePanel::applyFilter);
    bar->addWidget(filters_[i]);
  }
  bar->addStretch();
  auto* copy = new QToolButton(this);
  copy->setText("Copy");
  copy->setAutoRaise(true);
  copy->setToolTip("Copy the selected messages (all if none is selected)");
  bar->addWidget(copy);
  auto* clearButton = new QToolButton(this);
  clearButton->setText("Clear");
  clearButton->setAutoRaise(true);
  bar->addWidget(clearButton);
  v->addLayout(bar);

  list_ = new QTreeWidget(this);
  list_->setObjectName("messageList");
  list_->setColumnCount(2);
  list_->setHeaderHidden(true);
  list_->setRootIsDecorated(false);
  list_->setUniformRowHeights(true);
  list_->setSelectionMode(QAbstractItemView::ExtendedSelection);
  list_->setTextElideMode(Qt::ElideRight);  // the full text is in the tooltip
  list_->header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  list_->header()->setStretchLastSection(true);
  v->addWidget(list_);

  connect(clearButton, &QToolButton::clicked, this, &MessagePanel::clear);
  connect(copy, &QToolButton::clicked, this, [this] {
    QStringList lines;
    const auto selected = list_->selectedItems();
    for (int i = 0; i < list_->topLevelItemCount(); ++i) {
      QTreeWidgetItem* it = list_->topLevelItem(i);
      if (selected.isEmpty() || it->isSelected()) lines << it->text(0) + "  " + it->text(1);
    }
    QApplication::clipboard()->setText(lines.join('\n'));
  });
}

void MessagePanel::add(MessageLevel level, const QString& text) {
  auto* item = new QTreeWidgetItem(list_);
  item->setIcon(0, levelIcon(this, level));
  item->setText(0, QTime::currentTime().toString("HH:mm:ss"));
  item->setText(1, text);
  item->setToolTip(1, text);
  item->setData(0, kLevelRole, int(level));
  item->setForeground(0, QColor(140, 141, 146));
  if (level == MessageLevel::Error) item->setForeground(1, QColor(255, 140, 130));
  if (level == MessageLevel::Warning) item->setForeground(1, QColor(240, 200, 110));
  item->setHidden(!filters_[int(level)]->isChecked());
  ++counts_[int(level)];
  // A long session must not grow without bound: drop the oldest.
  while (list_->topLevelItemCount() > kMaxMessages) {
    QTreeWidgetItem* old = list_->takeTopLevelItem(0);
    --counts_[old->data(0, kLevelRole).toInt()];
    delete old;
  }
  list_->scrollToItem(item);
  const char* names[3] = {"Info", "Warnings", "Errors"};
  for (int i = 0; i < 3; ++i) filters_[i]->setText(QString("%1 %2").arg(counts_[i]).arg(names[i]));
  emit countsChanged();
}

void MessagePanel::clear() {
  list_->clear();
  counts_[0] = counts_[1] = counts_[2] = 0;
  const char* names[3] = {"Info", "Warnings", "Errors"};
  for (int i = 0; i < 3; ++i) filters_[i]->setText(QString("0 %1").arg(names[i]));
  emit countsChanged();
}

QString MessagePanel::text(int n) const {
  QTreeWidgetItem* it = list_->topLevelItem(n);
  return it ? it->text(1) : QString();
}

void MessagePanel::applyFilter() {
  for (int i = 0; i < list_->topLevelItemCount(); ++i) {
    QTreeWidgetItem* it = list_->topLevelItem(i);
    it->setHidden(!filters_[it->data(0, kLevelRole).toInt()]->isChecked());
  }
}

}  // namespace hs::app
