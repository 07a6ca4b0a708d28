#include "sequencer/keys.h"

namespace hs::sequencer {

const char* interpolationName(Interpolation i) {
  switch (i) {
    case Interpolation::Constant: return "constant";
    case Interpolation::Linear: return "linear";
    case Interpolation::Cubic: return "cubic";
  }
  return "?";
}

const char* tangentModeName(TangentMode m) {
  switch (m) {
    case TangentMode::Auto: return "auto";
    case TangentMode::User: return "user";
    case TangentMode::Broken: return "broken";
  }
  return "?";
}

const char* easeName(Ease e) {
  switch (e) {
    case Ease::None: return "none";
    case Ease::In: return "in";
    case Ease::Out: return "out";
    case Ease::InOut: return "in_out";
  }
  return "?";
}

std::optional<Interpolation> interpolationFromName(std::string_view s) {
  for (auto v : {Interpolation::Constant, Interpolation::Linear, Interpolation::Cubic})
    if (s == interpolationName(v)) return v;
  return std::nullopt;
}

std::optional<TangentMode> tangentModeFromName(std::string_view s) {
  for (auto v : {TangentMode::Auto, TangentMode::User, TangentMode::Broken})
    if (s == tangentModeName(v)) return v;
  return std::nullopt;
}

std::optional<Ease> easeFromName(std::string_view s) {
  for (auto v : {Ease::None, Ease::In, Ease::Out, Ease::InOut})
    if (s == easeName(v)) return v;
  return std::nullopt;
}

}  // namespace hs::sequencer
