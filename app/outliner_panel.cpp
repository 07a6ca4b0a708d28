#include "app/outliner_panel.h"

#include <QAction>
#include <QHeaderView>
#include <QMenu>
#include <QTreeView>
#include <QVBoxLayout>

#include "app/outliner_model.h"
#include "app/selection.h"

namespace hs::app {

OutlinerPanel::OutlinerPanel(scene::Document& doc, Selection& selection, QWidget* parent)
    : QWidget(parent), doc_(doc), selection_(selection) {
  setObjectName("outlinerPanel");
  model_ = new OutlinerModel(doc_, this);
  view_ = new QTreeView(this);
  view_->setObjectName("outlinerTree");
  view_->setModel(model_);
  view_->setHeaderHidden(true);
  view_->setUniformRowHeights(true);
  view_->setSelectionMode(QAbstractItemView::ExtendedSelection);
  view_->setSelectionBehavior(QAbstractItemView::SelectRows);
  view_->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed);
  view_->setDragEnabled(true);
  view_->setAcceptDrops(true);
  view_->setDropIndicatorShown(true);
  view_->setDragDropMode(QAbstractItemView::DragDrop);
  view_->setDefaultDropAction(Qt::MoveAction);
  view_->setContextMenuPolicy(Qt::CustomContextMenu);
  view_->setAnimated(false);
  view_->header()->setStretchLastSection(false);
  view_->header()->setSectionResizeMode(OutlinerModel::NameColumn, QHeaderView::Stretch);
  view_->header()->setSectionResizeMode(OutlinerModel::VisibleColumn, QHeaderView::Fixed);
  view_->header()->resizeSection(OutlinerModel::VisibleColumn, 28);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(view_);

  connect(view_->selectionModel(), &QItemSelectionModel::selectionChanged, this,
          [this] { pullSelectionFromView(); });
  connect(view_->selectionModel(), &QItemSelectionModel::currentChanged, this, [this] { pullSelectionFromView(); });
  connect(&selection_, &Selection::changed, this, &OutlinerPanel::pushSelectionToView);
  connect(model_, &OutlinerModel::rebuilt, this, [this] {
    restoreExpansion();
    pushSelectionToView();
  });
  connect(view_, &QTreeView::collapsed, this, [this](const QModelIndex& i) { collapsed_.insert(model_->idOf(i)); });
  connect(view_, &QTreeView::expanded, this, [this](const QModelIndex& i) { collapsed_.erase(model_->idOf(i)); });
  connect(view_, &QTreeView::customContextMenuRequested, this, [this](const QPoint& pos) {
    const QModelIndex at = view_->indexAt(pos);
    if (at.isValid() && !selection_.contains(model_->idOf(at))) selection_.select(model_->idOf(at));
    if (contextActions_.isEmpty()) return;
    QMenu menu(this);
    menu.addActions(contextActions_);
    menu.exec(view_->viewport()->mapToGlobal(pos));
  });
  restoreExpansion();
}

void OutlinerPanel::restoreExpansion() {
  // Everything is open unless the user closed it, so new groups show their content.
  syncing_ = true;
  std::vector<QModelIndex> stack;
  for (int r = 0; r < model_->rowCount(); ++r) stack.push_back(model_->index(r, 0));
  while (!stack.empty()) {
    const QModelIndex i = stack.back();
    stack.pop_back();
    const int rows = model_->rowCount(i);
    if (rows == 0) continue;
    view_->setExpanded(i, !collapsed_.count(model_->idOf(i)));
    for (int r = 0; r < rows; ++r) stack.push_back(model_->index(r, 0, i));
  }
  syncing_ = false;
}

void OutlinerPanel::pushSelectionToView() {
  if (syncing_) return;
  syncing_ = true;
  QItemSelection sel;
  for (scene::EntityId id : selection_.ids()) {
    const QModelIndex a = model_->indexOf(id, 0);
    if (!a.isValid()) continue;
    sel.select(a, model_->indexOf(id, OutlinerModel::ColumnCount - 1));
    for (QModelIndex p = a.parent(); p.isValid(); p = p.parent())
      if (!view_->isExpanded(p)) view_->expand(p);
  }
  view_->selectionModel()->select(sel, QItemSelectionModel::ClearAndSelect);
  const QModelIndex primary = model_->indexOf(selection_.primary(), 0);
  view_->selectionModel()->setCurrentIndex(primary, QItemSelectionModel::NoUpdate);
  if (primary.isValid()) view_->scrollTo(primary);
  syncing_ = false;
}

void OutlinerPanel::pullSelectionFromView() {
  if (syncing_) return;
  syncing_ = true;
  std::vector<scene::EntityId> ids;
  const scene::EntityId current = model_->idOf(view_->selectionModel()->currentIndex());
  bool currentSelected = false;
  for (const QModelIndex& i : view_->selectionModel()->selectedRows(0)) {
    const scene::EntityId id = model_->idOf(i);
    if (id == current) currentSelected = true;
    else ids.push_back(id);
  }
  // The item the user clicked last is the primary (what Properties shows).
  if (currentSelected) ids.push_back(current);
  selection_.set(std::move(ids));
  syncing_ = false;
}

void OutlinerPanel::renameSelected() {
  const QModelIndex i = model_->indexOf(selection_.primary(), 0);
  if (!i.isValid()) return;
  view_->setFocus();
  view_->edit(i);
}

}  // namespace hs::app
