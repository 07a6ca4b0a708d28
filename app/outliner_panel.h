#pragma once
// The Outliner dock: the hierarchy tree with in-place rename (double-click
// or F2), drag and drop reparenting and multi-selection, kept in step with
// the shared Selection.
#include <unordered_set>

#include <QWidget>

#include "scene/document.h"

class QTreeView;
class QItemSelection;

namespace hs::app {

class OutlinerModel;
class Selection;

class OutlinerPanel : public QWidget {
  Q_OBJECT
 public:
  OutlinerPanel(scene::Document& doc, Selection& selection, QWidget* parent = nullptr);

  OutlinerModel* model() const { return model_; }
  QTreeView* view() const { return view_; }
  // Actions offered on right-click (delete, duplicate, frame...).
  void setContextActions(const QList<QAction*>& actions) { contextActions_ = actions; }
  // Starts renaming the primary selected entity in place.
  void renameSelected();

 private:
  void pushSelectionToView();
  void pullSelectionFromView();
  void restoreExpansion();

  scene::Document& doc_;
  Selection& selection_;
  OutlinerModel* model_ = nullptr;
  QTreeView* view_ = nullptr;
  QList<QAction*> contextActions_;
  std::unordered_set<scene::EntityId> collapsed_;
  bool syncing_ = false;
};

}  // namespace hs::app
