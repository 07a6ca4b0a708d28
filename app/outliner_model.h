#pragma once
// The scene hierarchy as a Qt item model. It keeps its own copy of the tree
// shape and rebuilds it (deferred to the event loop) when the hierarchy
// changes, because a change can arrive from inside setData/dropMimeData and
// a model must not reset under a view that is still using its indexes.
// Renames and reparenting go through scene::ops / scene::Edit (undoable).
#include <unordered_map>
#include <vector>

#include <QAbstractItemModel>

#include "scene/document.h"

namespace hs::app {

class OutlinerModel : public QAbstractItemModel {
  Q_OBJECT
 public:
  static constexpr const char* kMimeType = "application/x-hybridscape-entities";
  enum Column { NameColumn = 0, VisibleColumn = 1, ColumnCount = 2 };

  explicit OutlinerModel(scene::Document& doc, QObject* parent = nullptr);

  scene::EntityId idOf(const QModelIndex& index) const;
  QModelIndex indexOf(scene::EntityId id, int column = 0) const;
  // Brings the model up to date now (normally done on the next event loop turn).
  void rebuildNow();

  // Moves `ids` (top-most of them) under `parent` (kNoEntity: top level)
  // before `row` of its children (-1: at the end), keeping world placement:
  // one undo step.
  bool moveEntities(const std::vector<scene::EntityId>& ids, scene::EntityId parent, int row);

  QModelIndex index(int row, int column, const QModelIndex& parent = {}) const override;
  QModelIndex parent(const QModelIndex& child) const override;
  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  bool setData(const QModelIndex& index, const QVariant& value, int role) override;
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override;
  Qt::ItemFlags flags(const QModelIndex& index) const override;

  Qt::DropActions supportedDropActions() const override { return Qt::MoveAction; }
  QStringList mimeTypes() const override { return {kMimeType}; }
  QMimeData* mimeData(const QModelIndexList& indexes) const override;
  bool canDropMimeData(const QMimeData* data, Qt::DropAction action, int row, int column,
                       const QModelIndex& parent) const override;
  bool dropMimeData(const QMimeData* data, Qt::DropAction action, int row, int column,
                    const QModelIndex& parent) override;

 signals:
  void aboutToRebuild();
  void rebuilt();

 private:
  struct Node {
    scene::EntityId parent = scene::kNoEntity;
    int row = 0;
    std::vector<scene::EntityId> children;
  };
  void onChanged(const scene::ChangeSet& changes);
  void scheduleRebuild();
  const std::vector<scene::EntityId>& childrenOf(scene::EntityId id) const;
  static std::vector<scene::EntityId> decode(const QMimeData* data);

  scene::Document& doc_;
  std::vector<scene::EntityId> roots_;
  std::unordered_map<scene::EntityId, Node> nodes_;
  bool rebuildPending_ = false;
};

}  // namespace hs::app
