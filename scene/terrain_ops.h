#pragma once
// Named terrain edits for the editor, the CLI and tests (as operations.h is
// for the rest): each is one undo step. Tile edits that take long (erosion,
// paint rules, DEM import into a terrain) are terrain_jobs.h.
#include <optional>
#include <string>
#include <vector>

#include <QString>

#include "core/params.h"
#include "scene/document.h"
#include "terrain/dem_import.h"
#include "terrain/heightfield.h"
#include "terrain/heightmap_image.h"

namespace hs::scene::ops {

// Ranges, units and help of NewTerrain are declared once in
// terrainNewOperation().
struct NewTerrain {
  std::string name = "Terrain";
  int samplesX = 1025, samplesY = 1025;         // per side
  glm::dvec2 sizeMetres{1024.0, 1024.0};        // first to last sample
  glm::dvec3 centre{0.0};                       // world position of the terrain's centre at height 0
  // What it starts as: flat at heightRange.min, or fractal hills spanning
  // heightRange (New Terrain dialog: a base to sculpt and erode).
  enum class Start { Flat, Hills };
  Start start = Start::Flat;
  terrain::HeightRange heightRange{0.0f, 100.0f};  // metres, relative to the centre's height
  uint64_t seed = 1;
  std::vector<terrain::Material> materials;     // empty: terrain::defaultMaterials()
  double lodErrorPixels = 1.0;
  // Show it on this existing entity (Properties > Add Component > Terrain)
  // instead of making a new one: centred on the entity, `centre` unused.
  EntityId showOn = kNoEntity;
};

// `terrain new` (the CLI) and the New Terrain dialog: size_m, samples,
// name, height_m, hills, seed, at, lod_error_px.
const OperationDecl& terrainNewOperation();

// A flat terrain and an entity showing it (its translation at `centre`), in
// one undo step. Returns the entity, or 0 with `error` (bad sizes, ...).
// With `spec.showOn`, that entity shows the new terrain instead (a terrain
// it showed before goes if nothing else shows it, as with setShownTerrain).
EntityId addTerrain(Document& doc, const NewTerrain& spec, std::string& error);

// A terrain from a heightfield made elsewhere (a DEM import keeps its CRS
// origin in the heightfield, so the entity stays at 0 and the terrain lands
// at its georeferenced place). Default materials and paint rules.
EntityId addTerrainFromHeightfield(Document& doc, terrain::Heightfield hf, const std::string& name,
                                   std::string& error, double lodErrorPixels = 1.0);

// A terrain from an imported DEM (`terrain import`, the editor's Import DEM):
// one rule for both. `name` given: it must be free, else 0 with `error`
// (the user asked for that name). `name` empty: named after `file` (its
// base name), and if that is taken the first free "<base> 2", "<base> 3",
// ... (importing a DEM twice is normal). `usedName` gets the name given.
EntityId addTerrainFromDem(Document& doc, terrain::Heightfield hf, const std::string& file, const std::string& name,
                           std::string& error, std::string* usedName = nullptr);

// Small values of a terrain (undoable like any field; `mergeKey` folds a
// drag or a colour pick into one step).
bool setTerrainMaterial(Document& doc, TerrainId id, int layer, const terrain::Material& m,
                        const QString& mergeKey = {});
// Rules are checked (known layer, finite values); blends and strength are
// clamped to their ranges. `mergeKey` folds a scrubbed spin box into one step.
bool setTerrainPaintRules(Document& doc, TerrainId id, std::vector<terrain::PaintRule> rules,
                          const QString& mergeKey = {});

// Which terrain entity `entity`'s terrain component shows (adding the
// component if it has none), one undo step. A terrain nothing shows any more
// leaves the document in the same step, as when its last entity is deleted
// (undo brings it back).
bool setShownTerrain(Document& doc, EntityId entity, TerrainId terrain);

// The terrain entity named `name` (entity or terrain name), or, with an
// empty name, the only terrain of the scene. 0 with `error` otherwise.
EntityId findTerrainEntity(const SceneState& state, const std::string& name, std::string& error);

// Writes every paint layer as a 16-bit PNG (or 8-bit, or EXR by extension)
// into `dir`: "<terrain>_<layer>_<material>.<ext>". Returns the files.
terrain::Result<std::vector<std::string>> exportPaintWeights(const TerrainAsset& t, const std::string& dir,
                                                             const std::string& extension = "png", int bits = 16);

}  // namespace hs::scene::ops
