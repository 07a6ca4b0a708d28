#pragma once
// Sequences to and from JSON (hs::Json, core/json.h). This is the form a
// sequence takes inside the .hscene document (scene_json embeds
// sequenceToJson()'s object under "sequence", and reads it back with
// readSequence) and in exported text files.
//
// Shape (members at their default value are left out, so files stay short
// and diff cleanly; members in this order):
// {"format": "hybridscape-sequence", "version": 1, "rate": [60, 1],
//  "start": 0, "end": 35999,
//  "bindings": [{"entity": 3, "label": "Camera",
//    "tracks": [{"type": "scalar", "property": "camera.fov_deg",
//                "keys": [{"t": 0.0, "v": 50.0}, {"t": 10.0, "v": 35.0, "interp": "linear", "ease": "in_out"}]}],
//    "path": {"points": [[0.0, 0.0, 10.0], ...], "progress": [{"t": 0.0, "v": 0.0, "interp": "linear"}, ...],
//             "aim": "tangent", "bank": true, "bank_scale": 1.0, "max_bank_deg": 30.0}}]}
// A binding of a material's tracks names it with "material": <material id>
// in place of "entity", the settings' binding with "settings": true
// (binding_target.h); their tracks' properties are "material.<field>" and
// "settings.<field>" (scene/fields.cpp). Those need version 2; a sequence
// with none of them is written as version 1, which older builds read.
// Rotation values are [w, x, y, z]; vector values [x, y, z]; slopes "in"
// and "out" (rotation slopes: body angular velocity, rad/s). Frames, rates
// and entity ids are whole numbers; times and values are doubles, written
// in the shortest form that reads back to the same double.
#include <optional>
#include <string>
#include <string_view>

#include "core/json.h"
#include "sequencer/sequence.h"

namespace hs::sequencer {

// 1: entity bindings; 2: material and settings bindings too; 3: camera
// cuts ("cuts": [{"camera": 3, "start": 0, "end": 599, "transition":
// "crossfade", "frames": 30, "ease": "in_out"}], camera_cuts.h; the
// transition members only when it is not a plain cut). A sequence is
// written with the lowest version that holds it.
inline constexpr int kSequenceFormatVersion = 3;

Json sequenceToJson(const Sequence& sequence);
// nullopt with `error` naming the place: "bindings[0].tracks[2].keys[5].interp:
// unknown interpolation 'cubc' (constant, linear, cubic)". A newer format
// version is refused with a message saying so.
std::optional<Sequence> sequenceFromJson(const Json& json, std::string& error);
// The same for a sequence inside a larger document: paths start at `path`
// ("sequence.bindings[0]..."), and the first failure goes to `reader`.
bool readSequence(JsonReader& reader, const Json& json, const std::string& path, Sequence& out);

// As text (pretty, ending in a newline). Reading names the line and column
// of a syntax error, and of a bad value after its path
// ("bindings[0].tracks[0].keys[0].interp (line 3, column 61): unknown ...").
std::string sequenceToJsonText(const Sequence& sequence);
std::optional<Sequence> sequenceFromJsonText(std::string_view text, std::string& error);

}  // namespace hs::sequencer
