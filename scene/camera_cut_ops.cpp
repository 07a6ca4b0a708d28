#include "scene/camera_cut_ops.h"

#include <algorithm>

#include "scene/edit.h"

namespace hs::scene {

std::string cutsProblem(const SceneState& state, const std::vector<sequencer::CameraCut>& cuts) {
  return sequencer::cutsProblem(
      cuts,
      [&](uint64_t id) {
        const Entity* e = state.find(EntityId(id));
        return e && e->camera.has_value();
      },
      [&](uint64_t id) {
        const Entity* e = state.find(EntityId(id));
        return e ? "'" + e->name + "' (#" + std::to_string(id) + ")" : "#" + std::to_string(id);
      });
}

std::vector<sequencer::CameraCut> withCut(std::vector<sequencer::CameraCut> cuts, const sequencer::CameraCut& cut) {
  cuts.insert(std::upper_bound(cuts.begin(), cuts.end(), cut,
                               [](const sequencer::CameraCut& a, const sequencer::CameraCut& b) {
                                 return a.start < b.start;
                               }),
              cut);
  return cuts;
}

namespace ops {

bool addCut(Document& doc, const sequencer::CameraCut& cut, std::string& error) {
  std::vector<sequencer::CameraCut> cuts = withCut(doc.state().sequence.cuts, cut);
  if (std::string p = cutsProblem(doc.state(), cuts); !p.empty()) {
    error = p;
    return false;
  }
  const Entity* camera = doc.state().find(EntityId(cut.camera));
  Edit e(doc, QString("Add Cut to %1").arg(QString::fromStdString(camera ? camera->name : std::string("camera"))));
  e.sequence().cuts = std::move(cuts);
  return e.commit();
}

bool removeCut(Document& doc, size_t index, std::string& error) {
  const std::vector<sequencer::CameraCut>& now = doc.state().sequence.cuts;
  if (index >= now.size()) {
    error = "no cut " + std::to_string(index + 1) + " (the timeline has " + std::to_string(now.size()) + ")";
    return false;
  }
  std::vector<sequencer::CameraCut> cuts = now;
  cuts.erase(cuts.begin() + std::ptrdiff_t(index));
  // The cut after it loses the shot its transition came from.
  if (index < cuts.size() && (index == 0 || cuts[index - 1].end + 1 != cuts[index].start)) {
    cuts[index].transition = sequencer::Transition::Cut;
    cuts[index].transitionFrames = 0;
  }
  Edit e(doc, "Remove Cut");
  e.sequence().cuts = std::move(cuts);
  return e.commit();
}

}  // namespace ops
}  // namespace hs::scene
