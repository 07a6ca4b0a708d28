#pragma once
// The camera-cut track in the document (sequencer/camera_cuts.h): its
// check against the scene's cameras, and the edits `hybridscape-cli cut
// add|remove` and the editor make, each one undo step that refuses (with
// the message naming the cut) what would leave the track unsound.
#include <optional>
#include <string>

#include "scene/camera_cuts_check.h"
#include "scene/document.h"
#include "sequencer/camera_cuts.h"

namespace hs::scene {

// `cuts` with `cut` inserted in its place by start frame (after cuts that
// start on the same frame).
std::vector<sequencer::CameraCut> withCut(std::vector<sequencer::CameraCut> cuts, const sequencer::CameraCut& cut);

namespace ops {
// Adds `cut` in its place by start frame. Refused, changing nothing, when
// the track would not be sound.
bool addCut(Document& doc, const sequencer::CameraCut& cut, std::string& error);
// Removes cut `index` (0-based); a transition into the cut after it that
// no longer has a cut right before becomes a plain cut.
bool removeCut(Document& doc, size_t index, std::string& error);
}  // namespace ops

}  // namespace hs::scene
