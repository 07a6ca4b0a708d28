#include "app/outliner_model.h"

#include <algorithm>

#include <QColor>
#include <QDataStream>
#include <QIODevice>
#include <QMimeData>
#include <QTimer>

#include "app/icons.h"
#include "scene/edit.h"
#include "scene/operations.h"

namespace hs::app {

OutlinerModel::OutlinerModel(scene::Document& doc, QObject* parent) : QAbstractItemModel(parent), doc_(doc) {
  connect(&doc_, &scene::Document::changed, this, &OutlinerModel::onChanged);
  rebuildNow();
}

void OutlinerModel::onChanged(const scene::ChangeSet& changes) {
  if (changes.hierarchy || changes.reset) {
    scheduleRebuild();
    return;
  }
  // Visibility and other per-entity values: repaint those rows only.
  for (scene::EntityId id : changes.entities) {
    const QModelIndex a = indexOf(id, 0), b = indexOf(id, ColumnCount - 1);
    if (a.isValid()) emit dataChanged(a, b);
  }
}

void OutlinerModel::scheduleRebuild() {
  if (rebuildPending_) return;
  rebuildPending_ = true;
  QTimer::singleShot(0, this, [this] {
    if (rebuildPending_) rebuildNow();
  });
}

void OutlinerModel::rebuildNow() {
  rebuildPending_ = false;
  emit aboutToRebuild();
  beginResetModel();
  const scene::SceneState& s = doc_.state();
  roots_ = s.roots;
  nodes_.clear();
  nodes_.reserve(s.entities.size());
  for (size_t i = 0; i < roots_.size(); ++i) nodes_[roots_[i]] = Node{scene::kNoEntity, int(i), {}};
  for (const auto& [id, e] : s.entities) {
    Node& n = nodes_[id];
    n.children = e.children;
    for (size_t i = 0; i < e.children.size(); ++i) {
      Node& c = nodes_[e.children[i]];
      c.parent = id;
      c.row = int(i);
    }
  }
  endResetModel();
  emit rebuilt();
}

const std::vector<scene::EntityId>& OutlinerModel::childrenOf(scene::EntityId id) const {
  if (id == scene::kNoEntity) return roots_;
  static const std::vector<scene::EntityId> none;
  auto it = nodes_.find(id);
  return it == nodes_.end() ? none : it->second.children;
}

scene::EntityId OutlinerModel::idOf(const QModelIndex& index) const {
  return index.isValid() ? scene::EntityId(index.internalId()) : scene::kNoEntity;
}

QModelIndex OutlinerModel::indexOf(scene::EntityId id, int column) const {
  auto it = nodes_.find(id);
  if (it == nodes_.end()) return {};
  return createIndex(it->second.row, column, quintptr(id));
}

QModelIndex OutlinerModel::index(int row, int column, const QModelIndex& parent) const {
  const auto& list = childrenOf(idOf(parent));
  if (row < 0 || size_t(row) >= list.size() || column < 0 || column >= ColumnCount) return {};
  return createIndex(row, column, quintptr(list[size_t(row)]));
}

QModelIndex OutlinerModel::parent(const QModelIndex& child) const {
  auto it = nodes_.find(idOf(child));
  if (it == nodes_.end() || it->second.parent == scene::kNoEntity) return {};
  return indexOf(it->second.parent, 0);
}

int OutlinerModel::rowCount(const QModelIndex& parent) const {
  if (parent.isValid() && parent.column() != 0) return 0;
  return int(childrenOf(idOf(parent)).size());
}

int OutlinerModel::columnCount(const QModelIndex&) const { return ColumnCount; }

QVariant OutlinerModel::data(const QModelIndex& index, int role) const {
  // The cached shape can be a turn behind the document: an entity that is
  // gone simply shows nothing until the rebuild.
  const scene::Entity* e = doc_.state().find(idOf(index));
  if (!e) return {};
  if (index.column() == NameColumn) {
    switch (role) {
      case Qt::DisplayRole:
      case Qt::EditRole: return QString::fromStdString(e->name);
      case Qt::DecorationRole:
        if (e->camera) return icon(Icon::Camera);
        if (e->light) return icon(e->light->type == scene::Light::Type::Sun ? Icon::Sun : Icon::PointLight);
        if (e->mesh) return icon(Icon::Mesh);
        return icon(e->children.empty() ? Icon::Empty : Icon::Group);
      case Qt::ToolTipRole: {
        QString tip = QString::fromStdString(e->name);
        if (e->mesh)
          if (const scene::MeshAsset* a = doc_.state().findAsset(e->mesh->mesh); a && a->data)
            tip += QString("\nMesh: %1 (%L2 triangles)").arg(QString::fromStdString(a->name)).arg(a->data->triangleCount());
        return tip;
      }
      case Qt::ForegroundRole:
        if (!doc_.state().effectivelyVisible(e->id)) return QColor(130, 131, 135);
        return {};
      default: return {};
    }
  }
  if (index.column() == VisibleColumn && role == Qt::CheckStateRole) return e->visible ? Qt::Checked : Qt::Unchecked;
  if (index.column() == VisibleColumn && role == Qt::ToolTipRole) return QString("Visible");
  return {};
}

bool OutlinerModel::setData(const QModelIndex& index, const QVariant& value, int role) {
  const scene::EntityId id = idOf(index);
  if (!doc_.state().find(id)) return false;
  if (index.column() == NameColumn && role == Qt::EditRole) {
    const QString name = value.toString().trimmed();
    if (name.isEmpty()) return false;
    return scene::ops::rename(doc_, id, name.toStdString());
  }
  if (index.column() == VisibleColumn && role == Qt::CheckStateRole) {
    const scene::EntityField* f = scene::findEntityField("entity.visible");
    return f && scene::ops::setField(doc_, id, *f, scene::FieldValue(value.toInt() == Qt::Checked));
  }
  return false;
}

QVariant OutlinerModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (orientation != Qt::Horizontal) return {};
  if (role == Qt::DisplayRole) return section == NameColumn ? QString("Name") : QString();
  if (role == Qt::ToolTipRole && section == VisibleColumn) return QString("Visible");
  return {};
}

Qt::ItemFlags OutlinerModel::flags(const QModelIndex& index) const {
  if (!index.isValid()) return Qt::ItemIsDropEnabled;  // drop on empty space: top level
  Qt::ItemFlags f = Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemIsDragEnabled | Qt::ItemIsDropEnabled;
  if (index.column() == NameColumn) f |= Qt::ItemIsEditable;
  if (index.column() == VisibleColumn) f |= Qt::ItemIsUserCheckable;
  return f;
}

QMimeData* OutlinerModel::mimeData(const QModelIndexList& indexes) const {
  QByteArray bytes;
  QDataStream out(&bytes, QIODevice::WriteOnly);
  std::vector<scene::EntityId> ids;
  for (const QModelIndex& i : indexes) {
    const scene::EntityId id = idOf(i);
    if (id != scene::kNoEntity && std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  }
  for (scene::EntityId id : ids) out << quint64(id);
  auto* data = new QMimeData;
  data->setData(kMimeType, bytes);
  return data;
}

std::vector<scene::EntityId> OutlinerModel::decode(const QMimeData* data) {
  std::vector<scene::EntityId> ids;
  if (!data || !data->hasFormat(kMimeType)) return ids;
  QByteArray bytes = data->data(kMimeType);
  QDataStream in(&bytes, QIODevice::ReadOnly);
  while (!in.atEnd()) {
    quint64 id = 0;
    in >> id;
    if (in.status() != QDataStream::Ok) break;
    ids.push_back(scene::EntityId(id));
  }
  return ids;
}

bool OutlinerModel::canDropMimeData(const QMimeData* data, Qt::DropAction action, int, int,
                                    const QModelIndex& parent) const {
  if (action != Qt::MoveAction) return false;
  const std::vector<scene::EntityId> ids = decode(data);
  if (ids.empty()) return false;
  // Refuse a drop onto an entity's own subtree (the outliner shows why by
  // not offering the drop at all).
  const scene::EntityId target = idOf(parent);
  for (scene::EntityId id : ids)
    if (target != scene::kNoEntity && doc_.state().isAncestorOrSelf(id, target)) return false;
  return true;
}

bool OutlinerModel::dropMimeData(const QMimeData* data, Qt::DropAction action, int row, int column,
                                 const QModelIndex& parent) {
  if (!canDropMimeData(data, action, row, column, parent)) return false;
  const std::vector<scene::EntityId> ids = decode(data);
  const scene::EntityId target = idOf(parent);
  // Applied after the view has finished its drop handling (see the header).
  QTimer::singleShot(0, this, [this, ids, target, row] { moveEntities(ids, target, row); });
  // Returning false keeps the view from deleting the "moved" rows itself:
  // the document change rebuilds the tree.
  return false;
}

bool OutlinerModel::moveEntities(const std::vector<scene::EntityId>& ids, scene::EntityId parent, int row) {
  const scene::SceneState& s = doc_.state();
  if (parent != scene::kNoEntity && !s.find(parent)) return false;
  const std::vector<scene::EntityId> top = scene::ops::topMost(s, ids);
  if (top.empty()) return false;
  // Where the block lands, counted among the siblings that stay.
  const std::vector<scene::EntityId>& siblings = parent == scene::kNoEntity ? s.roots : s.find(parent)->children;
  int landing = -1;
  if (row >= 0) {
    landing = 0;
    for (int i = 0; i < row && size_t(i) < siblings.size(); ++i)
      if (std::find(top.begin(), top.end(), siblings[size_t(i)]) == top.end()) ++landing;
  }
  scene::Edit e(doc_, top.size() == 1 ? QString("Reparent %1").arg(QString::fromStdString(s.find(top[0])->name))
                                      : QString("Reparent %1 entities").arg(top.size()));
  // First append them all (in order), then move the block into place: the
  // appended ones sit after every kept sibling, so the target indices are exact.
  // World placement is kept only across a change of parent: a reorder
  // among siblings leaves the transform bit-exact.
  for (scene::EntityId id : top)
    if (!e.reparent(id, parent, -1, e.peek(id)->parent != parent)) return false;
  if (landing >= 0)
    for (size_t i = 0; i < top.size(); ++i) e.reparent(top[i], parent, landing + int(i), false);
  return e.commit();
}

}  // namespace hs::app
