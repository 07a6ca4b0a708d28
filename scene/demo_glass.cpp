#include "scene/demo_glass.h"

#include <string>

#include "mesh/primitives.h"
#include "scene/demo_mesh.h"

namespace hs::scene {

constexpr const char* kHere = "scene/demo_glass.cpp";  // the assets' source path

void addDemoTranslucentSamples(SceneState& s) {
  const EntityId group = addDemoGroup(s, "Translucent samples");

  // Three glass-like spheres in front of the bunnies, in the first camera's
  // view (so the editor opens on them): low opacity, glossy, tinted;
  // two-sided, so each shows its far side through its near side, and the
  // bunnies and each other through both.
  const glm::vec3 tints[3] = {{0.75f, 0.9f, 1.0f}, {0.95f, 0.8f, 0.55f}, {0.7f, 1.0f, 0.75f}};
  const glm::dvec3 at[3] = {{-1.9, -4.2, 0.7}, {1.7, -3.6, 0.7}, {4.4, -1.4, 0.7}};
  for (int i = 0; i < 3; ++i) {
    Material& glass =
        addDemoMesh(s, "Glass sphere " + std::to_string(i + 1), mesh::uvSphere(0.7f, 48, 24), at[i], group, kHere);
    glass.baseColor = tints[i];
    glass.opacity = 0.22f;
    glass.roughness = 0.05f;
    glass.specular = 1.0f;
  }

  // A pond south-west of the bunnies, at the left edge of the first
  // camera's view, just above the flat ground: blue-green water through
  // which the ground shows.
  Material& water = addDemoMesh(s, "Pond (translucent water)", mesh::gridPlane(6.0f, 8, 3.0f), {-5.0, -2.5, 0.04},
                                group, kHere);
  water.baseColor = glm::vec3(0.08f, 0.28f, 0.32f);
  water.opacity = 0.6f;
  water.roughness = 0.08f;
  water.specular = 0.8f;
}

}  // namespace hs::scene
