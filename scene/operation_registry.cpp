#include "scene/operation_registry.h"

#include "foliage/foliage_operations.h"
#include "particles/particle_operations.h"
#include "scene/hscene_repair.h"
#include "scene/import_pipeline.h"
#include "scene/light_add_operation.h"
#include "scene/mesh_export_operation.h"
#include "scene/render_operation.h"
#include "scene/terrain_ops.h"
#include "sequencer/sequencer_operations.h"
#include "terrain/terrain_operations.h"

namespace hs::scene {

const std::vector<const OperationDecl*>& sharedOperations() {
  static const std::vector<const OperationDecl*> list = {
      &meshImportOperation(),
      &meshExportOperation(),
      &ops::terrainNewOperation(),
      &terrain::terrainImportOperation(),
      &terrain::terrainErodeOperation(),
      &terrain::terrainPaintRulesOperation(),
      &terrain::terrainLayerOperation(),
      &terrain::terrainExportOperation(),
      &renderOperation(),
      &sequencer::sequenceOperation(),
      &sequencer::keyOperation(),
      &sequencer::pathOperation(),
      &farmSlurmOperation(),
      &sequencer::farmVerifyOperation(),
      &repairOperation(),
      &lightAddOperation(),
      &foliage::foliageTypeAddOperation(),
      &foliage::foliageScatterOperation(),
      &foliage::foliageFillOperation(),
      &foliage::foliageClearOperation(),
      &foliage::foliagePlantOperation(),
      &foliage::foliageMoveOperation(),
      &foliage::foliageImpostorsOperation(),
      &particles::particlesAddOperation(),
  };
  return list;
}

const OperationDecl* findOperation(std::string_view name) {
  for (const OperationDecl* op : sharedOperations())
    if (op->name == name) return op;
  return nullptr;
}

}  // namespace hs::scene
