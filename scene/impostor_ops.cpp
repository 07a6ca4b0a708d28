#include "scene/impostor_ops.h"

#include <set>

#include "scene/edit.h"
#include "scene/impostor_key.h"

namespace hs::scene::ops {

std::vector<AssetId> impostorsToBake(const SceneState& state, bool all) {
  std::set<AssetId> ids;
  if (state.foliage)
    for (const foliage::FoliageType& t : state.foliage->store().types()) {
      if (!t.impostor) continue;
      const AssetId id = foliageTypeAsset(state, t);
      const MeshAsset* a = id != kNoAsset ? state.findAsset(id) : nullptr;
      if (a && a->data && (all || impostorStatus(state, *a) != ImpostorStatus::Stored)) ids.insert(id);
    }
  return {ids.begin(), ids.end()};
}

StoredImpostors storeImpostors(Document& doc, const std::vector<BakedImpostor>& baked) {
  StoredImpostors out;
  Edit e(doc, baked.size() == 1 ? QString("Bake impostor") : QString("Bake impostors"));
  for (const auto& [id, images] : baked) {
    const MeshAsset* a = doc.state().findAsset(id);
    if (!a || !images) {
      out.skipped.push_back("mesh asset " + std::to_string(id) + ": no longer in the scene");
      continue;
    }
    if (images->sourceKey != impostorSourceKey(doc.state(), *a)) {
      out.skipped.push_back("mesh asset '" + a->name + "': its mesh or materials changed during the bake");
      continue;
    }
    MeshAsset& w = e.asset(id);
    w.impostor = images;
    w.impostorHash = images->contentHash();
    ++out.stored;
  }
  if (out.stored > 0) e.commit();
  return out;
}

}  // namespace hs::scene::ops
