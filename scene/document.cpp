#include "scene/document.h"

#include <QUndoCommand>

namespace hs::scene {
namespace {

class PatchCommand : public QUndoCommand {
 public:
  PatchCommand(Document& doc, ScenePatch patch, const QString& text, const QString& mergeKey)
      : QUndoCommand(text), doc_(doc), patch_(std::move(patch)), mergeKey_(mergeKey) {}

  void redo() override { doc_.applyFromCommand(patch_, true); }
  void undo() override { doc_.applyFromCommand(patch_, false); }
  int id() const override { return mergeKey_.isEmpty() ? -1 : 1; }
  bool mergeWith(const QUndoCommand* other) override {
    const auto* o = dynamic_cast<const PatchCommand*>(other);
    if (!o || o->mergeKey_ != mergeKey_) return false;
    patch_.mergeLater(o->patch_);
    // A gesture that ends where it started (a drag back to its start, a
    // cancelled colour pick) changed nothing: QUndoStack drops the step.
    patch_.prune();
    setObsolete(patch_.empty());
    return true;
  }

 private:
  Document& doc_;
  ScenePatch patch_;
  QString mergeKey_;
};

ChangeSet describe(const ScenePatch& patch) {
  ChangeSet c;
  for (const auto& [id, ba] : patch.entities) {
    c.entities.push_back(id);
    if (!ba.before || !ba.after || ba.before->parent != ba.after->parent ||
        ba.before->children != ba.after->children || ba.before->name != ba.after->name)
      c.hierarchy = true;
  }
  if (patch.roots) c.hierarchy = true;
  c.assets = !patch.assets.empty();
  c.materials = !patch.materials.empty() || !patch.textures.empty();
  for (const auto& [id, ba] : patch.terrains) c.terrains.push_back(id);
  c.settings = patch.settings.has_value();
  c.sequence = patch.sequence.has_value();
  return c;
}

}  // namespace

Document::Document(QObject* parent) : QObject(parent) {
  qRegisterMetaType<hs::scene::ChangeSet>();
  connect(&undo_, &QUndoStack::cleanChanged, this, [this](bool clean) { emit modifiedChanged(!clean); });
}

Document::~Document() {
  // Commands refer back to this document; drop them before members go.
  undo_.clear();
}

bool Document::push(ScenePatch patch, const QString& text, const QString& mergeKey) {
  patch.prune();
  if (patch.empty()) return false;
  undo_.push(new PatchCommand(*this, std::move(patch), text, mergeKey));
  return true;
}

void Document::applyFromCommand(const ScenePatch& patch, bool forward) {
  applyPatch(state_, patch, forward);
  emit changed(describe(patch));
}

void Document::reset(SceneState state, const QString& filePath) {
  undo_.clear();
  state_ = std::move(state);
  nextEntity_ = state_.maxEntityId() + 1;
  nextAsset_ = state_.maxAssetId() + 1;
  nextTerrain_ = state_.maxTerrainId() + 1;
  nextMaterial_ = state_.maxMaterialId() + 1;
  nextTexture_ = state_.maxTextureId() + 1;
  undo_.setClean();
  setFilePath(filePath);
  ChangeSet c;
  c.reset = c.hierarchy = c.assets = c.materials = c.settings = c.sequence = true;
  emit changed(c);
  emit modifiedChanged(false);
}

void Document::notifyTerrainChanged(TerrainId id) {
  ChangeSet c;
  c.terrains.push_back(id);
  emit changed(c);
}

FoliageData& Document::foliage() { return foliageOf(state_); }

void Document::notifyFoliageChanged() {
  if (state_.foliage) state_.foliage->touch();
  ChangeSet c;
  c.foliage = true;
  emit changed(c);
}

void Document::setFilePath(const QString& path) {
  if (path == filePath_) return;
  filePath_ = path;
  emit filePathChanged(path);
}

}  // namespace hs::scene
