#include "sequencer/camera_cuts.h"

#include <algorithm>

#include "sequencer/interpolation.h"

namespace hs::sequencer {

namespace {
constexpr std::pair<Transition, const char*> kNames[] = {
    {Transition::Cut, "cut"},
    {Transition::Crossfade, "crossfade"},
    {Transition::DipToBlack, "dip_to_black"},
    {Transition::CrossfadeBlur, "crossfade_blur"},
    {Transition::Swipe, "swipe"},
    {Transition::WaterDrop, "water_drop"},
    {Transition::PixelDissolve, "pixel_dissolve"},
    {Transition::Glitch, "glitch"},
    {Transition::ZoomBlur, "zoom_blur"},
    {Transition::RadialWipe, "radial_wipe"},
};

std::string range(const CameraCut& c) { return std::to_string(c.start) + "-" + std::to_string(c.end); }
}  // namespace

const char* transitionName(Transition t) {
  for (const auto& [k, n] : kNames)
    if (k == t) return n;
  return "cut";
}

std::optional<Transition> transitionFromName(std::string_view s) {
  for (const auto& [k, n] : kNames)
    if (s == n) return k;
  return std::nullopt;
}

std::vector<std::string> transitionNameList() {
  std::vector<std::string> out;
  for (const auto& [k, n] : kNames) out.emplace_back(n);
  return out;
}

std::string transitionNames() {
  std::string out;
  for (const auto& [k, n] : kNames) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

bool isPatterned(Transition t) {
  return t != Transition::Cut && t != Transition::Crossfade && t != Transition::DipToBlack;
}

std::pair<float, float> Shot::weights() const {
  if (incoming == 0) return {1.0f, 0.0f};
  const double p = progress;
  if (isPatterned(transition)) return {float(1.0 - p), float(p)};
  switch (transition) {
    case Transition::Crossfade: return {float(1.0 - p), float(p)};
    case Transition::DipToBlack: return p < 0.5 ? std::pair{float(1.0 - 2.0 * p), 0.0f} : std::pair{0.0f, float(2.0 * p - 1.0)};
    default: break;
  }
  return {0.0f, 1.0f};
}

std::optional<Shot> shotAt(const std::vector<CameraCut>& cuts, int64_t frame) {
  // The last cut starting at or before the frame (cuts are sorted, apart).
  auto it = std::upper_bound(cuts.begin(), cuts.end(), frame,
                             [](int64_t f, const CameraCut& c) { return f < c.start; });
  if (it == cuts.begin()) return std::nullopt;
  const CameraCut& cut = *(it - 1);
  if (frame > cut.end) return std::nullopt;
  Shot shot;
  shot.camera = cut.camera;
  shot.cameraSince = cut.start;
  if (cut.transition == Transition::Cut || cut.transitionFrames <= 0 || it - 1 == cuts.begin()) return shot;
  const int64_t into = frame - cut.start;
  if (into >= cut.transitionFrames) return shot;  // done: this cut's camera alone
  const CameraCut& before = *(it - 2);
  shot.camera = before.camera;
  shot.cameraSince = before.start;
  if (into == 0) return shot;  // the first frame of a transition is the shot before, exactly
  shot.incoming = cut.camera;
  shot.incomingSince = cut.start;
  shot.transition = cut.transition;
  shot.progress = easeValue(cut.ease, double(into) / double(cut.transitionFrames));
  return shot;
}

std::string cutsProblem(const std::vector<CameraCut>& cuts, const std::function<bool(uint64_t)>& isCamera,
                        const std::function<std::string(uint64_t)>& cameraName) {
  for (size_t i = 0; i < cuts.size(); ++i) {
    const CameraCut& c = cuts[i];
    const std::string who = "cut " + std::to_string(i + 1) + " (frames " + range(c) + ")";
    if (c.end < c.start) return who + ": its end is before its start";
    if (!isCamera(c.camera))
      return who + ": camera " + cameraName(c.camera) + " is not a camera of the scene (deleted, or not a camera)";
    if (i > 0 && c.start <= cuts[i - 1].end)
      return who + ": it overlaps cut " + std::to_string(i) + " (frames " + range(cuts[i - 1]) + ")";
    if (c.transition == Transition::Cut) {
      if (c.transitionFrames != 0) return who + ": a plain cut has no transition length";
      continue;
    }
    const std::string t = std::string(transitionName(c.transition));
    if (i == 0) return who + ": the first cut has no shot before it to " + t + " from";
    if (c.transitionFrames <= 0) return who + ": its " + t + " needs a length of at least 1 frame";
    if (cuts[i - 1].end + 1 != c.start)
      return who + ": its " + t + " needs cut " + std::to_string(i) + " to end on frame " +
             std::to_string(c.start - 1) + " (it ends on " + std::to_string(cuts[i - 1].end) + ")";
    const int64_t here = c.end - c.start, before = cuts[i - 1].end - cuts[i - 1].start;
    if (c.transitionFrames > here || c.transitionFrames > before)
      return who + ": its " + t + " of " + std::to_string(c.transitionFrames) + " frames is longer than " +
             (c.transitionFrames > here ? "this shot" : "the shot before") + " (" +
             std::to_string(c.transitionFrames > here ? here : before) + " frames after its first)";
  }
  return "";
}

}  // namespace hs::sequencer
