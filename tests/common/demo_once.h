#pragma once
// The demo scene built once per test process, for tests that start from it
// (the post and stylised goldens). Null, with the reason on the test log,
// when it cannot be built.
#include <QtGlobal>

#include <optional>
#include <string>

#include "scene/demo_scene.h"

namespace hs::test {

inline const scene::SceneState* demoOnce() {
  static const std::optional<scene::SceneState> demo = [] {
    std::string error;
    std::optional<scene::SceneState> s = scene::buildDemoScene(error);
    if (!s) qWarning("the demo scene: %s", error.c_str());
    return s;
  }();
  return demo ? &*demo : nullptr;
}

}  // namespace hs::test
