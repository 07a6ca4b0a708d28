#pragma once
// Camera cuts (docs/sequencer.md "Camera cuts"): which camera is live over
// which frames, as Unreal Sequencer's camera-cut track, with a transition
// from one cut into the next. A frame's shot is a pure function of the
// frame (DESIGN.md, "Time and determinism"): no state from the frame
// before, so a farm chunk and a whole export show the same.
//
// A cut's transition occupies frames [start, start + transitionFrames]:
// frame `start` shows the cut before exactly (progress 0), frame
// `start + transitionFrames` this cut's camera exactly (progress 1), the
// frames between both cameras combined (render/stereo_frame_source.h
// renders them as two view groups of one frame). The outgoing camera keeps
// moving as its tracks say while it fades out. Frames outside every cut
// show the sequence's own camera (the one a render is told, or the shot
// camera), as without cuts.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sequencer/keys.h"

namespace hs::sequencer {

// How a cut begins. Cut: at once. Crossfade: the two shots' light mixed,
// (1 - p) and p. DipToBlack: the outgoing shot to black by the middle,
// then the incoming one up from black. The rest are stylised, drawn as a
// pattern over the screen (shaders/group_combine.frag, docs/sequencer.md
// "Transitions"): CrossfadeBlur (both shots blurred towards the middle),
// Swipe (an edge across the screen), WaterDrop (a ring spreading from the
// centre with a ripple ahead of it), PixelDissolve (blocks growing to the
// middle, each switching at its own moment), Glitch (bands displaced and
// split by channel, switching band by band, seeded by the frame), ZoomBlur
// (a radial blur that peaks at the middle), RadialWipe (a clock hand).
enum class Transition : uint8_t {
  Cut,
  Crossfade,
  DipToBlack,
  CrossfadeBlur,
  Swipe,
  WaterDrop,
  PixelDissolve,
  Glitch,
  ZoomBlur,
  RadialWipe,
};
const char* transitionName(Transition t);                     // "cut", "crossfade", "dip_to_black", ...
std::optional<Transition> transitionFromName(std::string_view s);
std::string transitionNames();                                 // "cut, crossfade, dip_to_black, ..."
std::vector<std::string> transitionNameList();                 // the same, one by one (CLI choices, menus)
// Whether the two shots are combined by a pattern over the screen rather
// than by weights alone (everything but Cut, Crossfade and DipToBlack).
bool isPatterned(Transition t);

struct CameraCut {
  uint64_t camera = 0;  // scene::EntityId of a camera entity
  int64_t start = 0;    // first frame, inclusive
  int64_t end = 0;      // last frame, inclusive
  Transition transition = Transition::Cut;  // from the cut before into this one
  int64_t transitionFrames = 0;             // its length; 0 with Cut
  Ease ease = Ease::InOut;                  // the transition's progress over its frames
  bool operator==(const CameraCut&) const = default;
};

// What a frame shows: `camera` alone, or, during a transition, `camera`
// (outgoing) and `incoming` combined at `progress` in (0, 1).
struct Shot {
  uint64_t camera = 0;
  uint64_t incoming = 0;  // 0: one camera
  Transition transition = Transition::Cut;
  double progress = 0.0;  // eased
  // The first frame of each camera's cut (`camera`'s, `incoming`'s): where
  // a shot's history begins (automatic exposure adapts from there).
  int64_t cameraSince = 0;
  int64_t incomingSince = 0;
  // The two cameras' weights in the combined light (outgoing, incoming);
  // for a patterned transition, the share of the screen each covers
  // (1 - p, p), which is also how "the stronger shot" is chosen.
  std::pair<float, float> weights() const;
};

// The shot at `frame`; nullopt where no cut covers it. `cuts` must be
// sound (cutsProblem returns "").
std::optional<Shot> shotAt(const std::vector<CameraCut>& cuts, int64_t frame);

// Why `cuts` cannot be rendered, naming the cut ("cut 2 (frames 300-200):
// its end is before its start"), or "" when sound: each cut's range in
// order (start <= end), sorted and not overlapping, a camera that
// `isCamera` knows, a transition only into a cut right after another
// (no gap), with a length > 0, not longer than either shot, and none on
// the first cut. `cameraName` names a camera in messages.
std::string cutsProblem(const std::vector<CameraCut>& cuts, const std::function<bool(uint64_t)>& isCamera,
                        const std::function<std::string(uint64_t)>& cameraName);

}  // namespace hs::sequencer
