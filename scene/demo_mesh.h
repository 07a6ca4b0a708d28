#pragma once
// Building blocks of the demo's sample groups made in code (the surface
// detail slabs, the translucent samples): a group under the roots, and a
// mesh made in code as an asset of its own, shown once in a group.
#include <string>

#include "mesh/mesh_data.h"
#include "scene/scene_state.h"

namespace hs::scene {

// An empty group entity named `name` at the roots; returns its id.
EntityId addDemoGroup(SceneState& state, const std::string& name);

// `mesh` (its first material named "surface") as a new asset with its own
// material, shown once at `position` under `parent`; `madeIn` names the
// source file for the asset's source path. Returns the material for the
// caller to fill.
Material& addDemoMesh(SceneState& state, const std::string& name, mesh::MeshData mesh, const glm::dvec3& position,
                      EntityId parent, const std::string& madeIn);

}  // namespace hs::scene
