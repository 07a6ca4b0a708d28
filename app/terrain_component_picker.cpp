#include "app/terrain_component_picker.h"

#include <QMenu>

#include "scene/terrain_ops.h"

namespace hs::app {
namespace {

constexpr int kNewTerrain = -1;

// "Valley", or "Valley (terrain 3)" when two terrains share the name.
QString terrainLabel(const scene::SceneState& s, const scene::TerrainAsset& t) {
  int same = 0;
  for (const auto& [id, other] : s.terrains) same += other.name == t.name;
  const QString name = QString::fromStdString(t.name);
  return same > 1 ? QString("%1 (terrain %2)").arg(name).arg(t.id) : name;
}

const char* kLosesTerrain =
    "A terrain that no entity shows any more leaves the scene with this change (Undo brings it back).";

}  // namespace

void fillTerrainComponentMenu(QMenu* menu, scene::Document& doc, scene::EntityId entity, const NewTerrainHook& newTerrain) {
  menu->setObjectName("addTerrainComponentMenu");
  menu->setToolTipsVisible(true);
  // Filled now (tests trigger its actions) and again each time it opens:
  // terrains come and go while the Properties panel keeps its sections.
  if (!menu->property("hsFilledOnShow").toBool()) {
    menu->setProperty("hsFilledOnShow", true);
    QObject::connect(menu, &QMenu::aboutToShow, menu, [menu, &doc, entity, newTerrain] {
      menu->clear();
      fillTerrainComponentMenu(menu, doc, entity, newTerrain);
    });
  }
  const scene::SceneState& s = doc.state();
  for (const auto& [id, t] : s.terrains) {
    QAction* a = menu->addAction(QString("Show %1").arg(terrainLabel(s, t)));
    a->setToolTip("Show this terrain here too (the entity's translation moves it)");
    a->setData(qlonglong(id));
    const scene::TerrainId tid = id;
    QObject::connect(a, &QAction::triggered, menu, [&doc, entity, tid] { scene::ops::setShownTerrain(doc, entity, tid); });
  }
  if (newTerrain) {
    if (!s.terrains.empty()) menu->addSeparator();
    QAction* a = menu->addAction("New Terrain…");
    a->setObjectName("addNewTerrainComponent");
    a->setToolTip("Make a terrain centred on this entity");
    QObject::connect(a, &QAction::triggered, menu, [newTerrain, entity] { newTerrain(entity); });
  }
  if (menu->isEmpty()) {
    QAction* a = menu->addAction("No terrains yet: Terrain > New Terrain… or Import DEM…");
    a->setEnabled(false);
  }
}

TerrainPicker::TerrainPicker(scene::Document& doc, scene::EntityId entity, NewTerrainHook newTerrain, QWidget* parent)
    : QComboBox(parent), doc_(doc), entity_(entity), newTerrain_(std::move(newTerrain)) {
  setObjectName("terrainPicker");
  setToolTip(QString("The terrain this entity shows. ") + kLosesTerrain);
  setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  setMinimumContentsLength(6);
  connect(this, &QComboBox::activated, this, &TerrainPicker::chosen);
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.reset || c.hierarchy || !c.terrains.empty() || !c.entities.empty()) refresh();
  });
  refresh();
}

void TerrainPicker::refresh() {
  const scene::SceneState& s = doc_.state();
  const scene::Entity* e = s.find(entity_);
  if (!e) return;
  const scene::TerrainId shown = e->terrain ? e->terrain->terrain : scene::kNoTerrain;
  updating_ = true;
  clear();
  int current = -1;
  if (!s.findTerrain(shown)) {
    // An old file or a script may have left it empty: say so, it draws nothing.
    addItem("(none: choose a terrain)", QVariant());
    current = 0;
  }
  for (const auto& [id, t] : s.terrains) {
    if (id == shown) current = count();
    addItem(terrainLabel(s, t), qlonglong(id));
  }
  if (newTerrain_) addItem("New Terrain…", kNewTerrain);
  setCurrentIndex(current);
  updating_ = false;
}

void TerrainPicker::chosen(int index) {
  if (updating_) return;
  const QVariant v = itemData(index);
  if (!v.isValid()) return;
  if (v.toLongLong() == kNewTerrain) {
    refresh();  // back to what it shows until the dialog makes one
    if (newTerrain_) newTerrain_(entity_);
    return;
  }
  scene::ops::setShownTerrain(doc_, entity_, scene::TerrainId(v.toLongLong()));
}

}  // namespace hs::app
