#pragma once
// Sequences to and from JSON (sequencer/json.h). This is the form a
// sequence takes inside the .hscene document (scene_json embeds
// sequenceToJson()'s object under "sequence") and in exported text files.
//
// Shape (members at their default value are left out, so files stay short
// and diff cleanly):
// {"format": "hybridscape-sequence", "version": 1, "rate": [60, 1],
//  "start": 0, "end": 35999,
//  "bindings": [{"entity": 3, "label": "Camera",
//    "tracks": [{"type": "scalar", "property": "camera.fov_deg",
//                "keys": [{"t": 0, "v": 50}, {"t": 10, "v": 35, "interp": "linear", "ease": "in_out"}]}],
//    "path": {"points": [[0,0,10], ...], "progress": [{"t": 0, "v": 0, "interp": "linear"}, ...],
//             "aim": "tangent", "bank": true, "max_bank_deg": 30}}]}
// Rotation values are [w, x, y, z]; vector values [x, y, z]; slopes "in"
// and "out" (rotation slopes: body angular velocity, rad/s).
#include <optional>
#include <string>
#include <string_view>

#include "sequencer/json.h"
#include "sequencer/sequence.h"

namespace hs::sequencer {

inline constexpr int kSequenceFormatVersion = 1;

JsonValue sequenceToJson(const Sequence& sequence);
// nullopt with `error` naming the place: "bindings[0].tracks[2].keys[5].interp:
// unknown interpolation 'cubc' (constant, linear, cubic)". A newer format
// version is refused with a message saying so.
std::optional<Sequence> sequenceFromJson(const JsonValue& json, std::string& error);

std::string sequenceToJsonText(const Sequence& sequence);
std::optional<Sequence> sequenceFromJsonText(std::string_view text, std::string& error);

}  // namespace hs::sequencer
