#include "scene/demo_dof.h"

namespace hs::scene {

void addDemoFocusPull(SceneState& s) {
  const EntityId id = s.findByName("Flight Camera");
  Entity* cam = id ? &s.entities.at(id) : nullptr;
  if (!cam || !cam->camera) return;
  cam->camera->fStop = 2.8;
  cam->camera->focusDistance = 8.1;  // the flight's aim point, 8 m across and 1-2 m below
  auto key = [](double t, double v) {
    sequencer::ScalarKey k;
    k.time = t;
    k.value = v;
    k.interpolation = sequencer::Interpolation::Linear;
    k.ease = sequencer::Ease::InOut;
    return k;
  };
  sequencer::ScalarTrack focus{"camera.focus_distance_m", {}};
  focus.keys = {key(0.0, 8.1), key(3.0, 8.1), key(5.0, 30.0), key(7.0, 30.0), key(9.0, 8.1)};
  for (sequencer::Binding& b : s.sequence.bindings)
    if (b.entity == id) {
      b.tracks.push_back(focus);
      return;
    }
}

}  // namespace hs::scene
