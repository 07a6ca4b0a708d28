#pragma once
// The foliage operations the editor and `hybridscape-cli foliage` will
// share, declared once (core/params.h), as terrain/terrain_operations.h
// does for the terrain: `foliage type add`, `foliage scatter`, `foliage
// clear` and `foliage plant`, with the helpers that turn their checked
// values (a JSON object keyed by the declarations, as paramsJson() and the
// CLI's parser give) into the domain's structs.
#include <optional>
#include <string>

#include "core/params.h"
#include "foliage/foliage_type.h"
#include "foliage/plants.h"
#include "foliage/surface.h"

namespace hs::foliage {

// `foliage type add NAME --mesh ASSET [type options] SCENE`.
const OperationDecl& foliageTypeAddOperation();
// `foliage scatter TYPE SCENE [--density N] [--region x0,y0,x1,y1]
// [--layer NAME] [--slope a,b] [--altitude a,b] [--on terrain|meshes|both]
// [--seed S]`: the rule-based scatter of one type, the options overriding
// the type's own rules for this scatter.
const OperationDecl& foliageScatterOperation();
// `foliage fill TYPE SCENE --layer NAME [--min-weight W] [--region
// x0,y0,x1,y1] [--seed S]`: the type painted to its density wherever the
// terrain's paint layer weighs at least W (the editor's Fill Paint Layer).
const OperationDecl& foliageFillOperation();
// `foliage clear TYPE SCENE [--region x0,y0,x1,y1]`.
const OperationDecl& foliageClearOperation();
// `foliage move TYPE SCENE --offset dx,dy,dz [--region x0,y0,x1,y1]
// [--keep-height]`: the type's instances (in the region) moved by an exact
// offset, each put back on the ground unless --keep-height (the editor's
// Move Selected Instances By… takes the same offset for its selection).
const OperationDecl& foliageMoveOperation();
// `foliage impostors SCENE [--all]`: bake and store the impostors of the
// meshes foliage types draw with one (scene/impostor_ops.h).
const OperationDecl& foliageImpostorsOperation();
// `foliage plant NAME --kind broadleaf|conifer|shrub|grass|rock [--seed S] SCENE`.
const OperationDecl& foliagePlantOperation();

// A type named `name` from `foliage type add`'s values (declared keys;
// absent ones take their defaults). False with `error` naming the option.
bool typeFromValues(const std::string& name, const Json& values, FoliageType& out, std::string& error);
// `type` with `foliage scatter`'s overrides applied (density, layer,
// slope, altitude, surfaces).
FoliageType scatterRules(const FoliageType& type, const Json& values);
// `--region x0,y0,x1,y1` as a rectangle; nullopt when not given.
std::optional<Region2> regionFromValues(const Json& values);
// `foliage plant`'s values as the generator's parameters.
PlantParams plantFromValues(const Json& values);

}  // namespace hs::foliage
