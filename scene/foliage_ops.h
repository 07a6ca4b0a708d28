#pragma once
// The foliage operations on a document, shared by the editor and
// `hybridscape-cli foliage` (declared once in foliage/foliage_operations.h):
// each changes the document's foliage (foliage_data.h) through the domain's
// tools and records one undo step (foliage_command.h). Messages name the
// type and what was capped, refused or dropped.
#include <optional>
#include <string>
#include <vector>

#include "foliage/plants.h"
#include "foliage/tools.h"
#include "scene/document.h"
#include "scene/foliage_ground.h"

namespace hs::scene::ops {

struct FoliageOutcome {
  bool ok = true;
  std::string error;                  // when !ok: what was refused, naming the type or asset
  std::vector<std::string> messages;  // warnings (clamped values, caps)
  foliage::OpStats stats;
  std::string summary;                // one line: what changed
  bool cancelled = false;             // commitFoliageWork: the work was cancelled, nothing changed
};

// Adds a type drawing the mesh asset `type.mesh` (which must exist).
FoliageOutcome addFoliageType(Document& doc, const foliage::FoliageType& type);
// Replaces type `index`'s settings (its name may change if free).
FoliageOutcome setFoliageType(Document& doc, size_t index, const foliage::FoliageType& type);

// The rule-based scatter of one type (or, with `types` empty, of every type
// in order, competing for room) over the ground or a region. `rules`: the
// type's rules with `foliage scatter`'s overrides (foliage::scatterRules);
// nullopt: the type's own.
FoliageOutcome scatterFoliage(Document& doc, const FoliageGround& ground, const foliage::TypeSet& types,
                              uint64_t seed, const std::optional<foliage::Region2>& region = std::nullopt,
                              const std::optional<foliage::FoliageType>& rules = std::nullopt,
                              unsigned threads = 0);
// scatterFoliage's work on any store (the document's, or a copy a worker
// edits off the UI thread, reporting to `progress`, which may cancel):
// its result and the undo step's text, or `error` with the store untouched.
struct FoliageWork {
  foliage::EditResult result;
  QString text;
  std::string error;
};
FoliageWork scatterOnStore(foliage::FoliageStore& store, const FoliageGround& ground, const foliage::TypeSet& types,
                           uint64_t seed, const std::optional<foliage::Region2>& region = std::nullopt,
                           const std::optional<foliage::FoliageType>& rules = std::nullopt, unsigned threads = 0,
                           const Progress* progress = nullptr);
// Puts the work a copy of the document's store (`worked`, copied while the
// document's was as it is now) went through into the document as one undo
// step: the cells the work touched replace the document's. `worked` is as
// it was copied after. A cancelled work changes nothing; nor does one whose
// cells, ids or types the document changed meanwhile (refused, saying so).
FoliageOutcome commitFoliageWork(Document& doc, foliage::FoliageStore& worked, FoliageWork work);

// A brush dab (or a fill of an area: `fill` true).
FoliageOutcome paintFoliage(Document& doc, const FoliageGround& ground, const foliage::PaintParams& params,
                            bool fill = false, const QString& text = "Paint foliage");
// foliage::fillLayer as one undo step: `types` painted to their density
// where the terrain's paint layer `layer` weighs at least `minWeight`
// (within `region`, else the whole terrain).
FoliageOutcome fillFoliageLayer(Document& doc, const FoliageGround& ground, const foliage::TypeSet& types,
                                const std::string& layer, double minWeight, uint64_t seed,
                                const std::optional<foliage::Region2>& region = std::nullopt);
// fillFoliageLayer's work on any store (as scatterOnStore: a copy a worker
// edits, `progress` may cancel); commitFoliageWork puts it in the document.
FoliageWork fillLayerOnStore(foliage::FoliageStore& store, const FoliageGround& ground, const foliage::TypeSet& types,
                             const std::string& layer, double minWeight, uint64_t seed,
                             const std::optional<foliage::Region2>& region = std::nullopt,
                             const Progress* progress = nullptr);
// Removes the types' (or every type's) instances in the region (nullopt:
// everywhere).
FoliageOutcome eraseFoliage(Document& doc, const std::optional<foliage::Region2>& region,
                            const foliage::TypeSet& types, const QString& text = "Erase foliage");

// Moves the types' (or every type's) instances in the region (nullopt:
// everywhere) by `offset`; with `snap` each is put back on `ground` under
// its new place (foliage::moveSelection). One undo step.
FoliageOutcome moveFoliage(Document& doc, const FoliageGround& ground, const foliage::TypeSet& types,
                           const std::optional<foliage::Region2>& region, const glm::dvec3& offset, bool snap);

// A generated plant's asset (foliage/plants.h: its mesh and LOD chain, no
// id, no materials yet); `error` when the generator failed.
std::optional<MeshAsset> makePlantAsset(const std::string& name, const foliage::PlantParams& params,
                                        std::string& error, foliage::PlantStats* stats = nullptr);
// A plant material's look: leaves and blades (textured: their alpha is the
// outline) cut out, two-sided and letting 30 % of the light through (transmission);
// bark and rock opaque and one-sided.
void applyPlantLook(Material& m);

// A generated plant (foliage/plants.h) with its LOD chain as a mesh asset
// (no entity: foliage types draw it), its leaves a two-sided cut-out
// material. Returns the asset's id, or kNoAsset with `error`.
AssetId addPlantAsset(Document& doc, const std::string& name, const foliage::PlantParams& params,
                      std::string& error, foliage::PlantStats* stats = nullptr);

}  // namespace hs::scene::ops
