#include "scene/emitter_tracks.h"

#include <algorithm>

#include "core/params.h"
#include "sequencer/binding_target.h"
#include "sequencer/track.h"

namespace hs::scene {
namespace {

std::string spawnKeyList() {
  std::string s;
  for (const std::string& k : particles::spawnKeys()) s += (s.empty() ? "" : ", ") + k;
  return s;
}

}  // namespace

bool isEmitterTrack(std::string_view property) {
  return property.substr(0, kEmitterTrackPrefix.size()) == kEmitterTrackPrefix;
}

std::optional<std::string> emitterTrackKey(std::string_view property, std::string* error) {
  if (!isEmitterTrack(property)) return std::nullopt;
  const std::string key(property.substr(kEmitterTrackPrefix.size()));
  if (particles::isSpawnKey(key)) return key;
  if (error)
    *error = "'" + std::string(property) + "' cannot be animated: an emitter's timeline tracks are its spawn values (" +
             spawnKeyList() + "), sampled at each particle's birth; the rate, wind and bursts have keys of their own";
  return std::nullopt;
}

std::optional<sequencer::PropertyValue> emitterKeyValue(const particles::EmitterDesc& d, std::string_view key) {
  const std::vector<double> x = particles::spawnValue(particles::spawnValues(d), key);
  if (x.size() == 3) return sequencer::PropertyValue(glm::dvec3(x[0], x[1], x[2]));
  if (x.size() == 1) return sequencer::PropertyValue(x[0]);
  return std::nullopt;
}

std::optional<sequencer::PropertyValue> parseEmitterKeyValue(std::string_view key, std::string_view text,
                                                             std::string& error) {
  if (!particles::isSpawnKey(key)) {
    emitterTrackKey(std::string(kEmitterTrackPrefix) + std::string(key), &error);
    return std::nullopt;
  }
  // A pair's key is one number (its centre) in the pair's range.
  ParamDecl d = paramIn(particles::emitterParamDecls(), key);
  const bool vector = particles::spawnValueCount(key) == 3;
  d.count = vector ? 3 : 1;
  d.ordered = false;
  d.oneForAll = false;
  d.valueName = vector ? "X,Y,Z" : "VALUE";
  std::string why;
  const std::optional<Json> v = parseParam(d, std::string(text), why);
  if (!v) {
    error = "particles." + std::string(key) + ": " + why;
    return std::nullopt;
  }
  if (vector) return sequencer::PropertyValue(glm::dvec3((*v)[0].get<double>(), (*v)[1].get<double>(), (*v)[2].get<double>()));
  return sequencer::PropertyValue(v->get<double>());
}

std::shared_ptr<const EmitterSpawnTracks> EmitterSpawnTracks::of(const SceneState& state, EntityId id) {
  const sequencer::Binding* b = state.sequence.findBinding(id);
  if (!b) return nullptr;
  auto out = std::make_shared<EmitterSpawnTracks>();
  for (const sequencer::Track& t : b->tracks) {
    const std::optional<std::string> key = emitterTrackKey(sequencer::trackProperty(t));
    if (!key || sequencer::trackKeyCount(t) == 0) continue;
    // A track of the wrong kind for its key writes nothing (the load checks drop it).
    const bool vector = particles::spawnValueCount(*key) == 3;
    if (vector ? !std::holds_alternative<sequencer::VectorTrack>(t) : !std::holds_alternative<sequencer::ScalarTrack>(t))
      continue;
    out->tracks_.push_back({particles::spawnSlot(*key), t});
  }
  if (out->tracks_.empty()) return nullptr;
  return out;
}

void EmitterSpawnTracks::apply(double birth, particles::SpawnValues& v) const {
  for (const SlotTrack& st : tracks_) {
    if (const auto* s = std::get_if<sequencer::ScalarTrack>(&st.track)) {
      if (const std::optional<double> x = sequencer::evaluate(*s, birth)) particles::setSpawnValue(v, st.slot, &*x);
    } else if (const auto* w = std::get_if<sequencer::VectorTrack>(&st.track)) {
      if (const std::optional<glm::dvec3> x = sequencer::evaluate(*w, birth)) {
        const double xyz[3] = {x->x, x->y, x->z};
        particles::setSpawnValue(v, st.slot, xyz);
      }
    }
  }
}

std::pair<particles::SpawnValues, particles::SpawnValues> EmitterSpawnTracks::range(
    const particles::SpawnValues& base, double t0, double t1) const {
  std::pair<particles::SpawnValues, particles::SpawnValues> r{base, base};
  for (const SlotTrack& st : tracks_) {
    if (const auto* s = std::get_if<sequencer::ScalarTrack>(&st.track)) {
      if (const auto x = sequencer::valueRange(*s, t0, t1)) {
        particles::setSpawnValue(r.first, st.slot, &x->first);
        particles::setSpawnValue(r.second, st.slot, &x->second);
      }
    } else if (const auto* w = std::get_if<sequencer::VectorTrack>(&st.track)) {
      if (const auto x = sequencer::valueRange(*w, t0, t1)) {
        const double lo[3] = {x->first.x, x->first.y, x->first.z}, hi[3] = {x->second.x, x->second.y, x->second.z};
        particles::setSpawnValue(r.first, st.slot, lo);
        particles::setSpawnValue(r.second, st.slot, hi);
      }
    }
  }
  return r;
}

void checkEmitterTracks(SceneState& state, std::vector<std::string>* warnings) {
  for (sequencer::Binding& b : state.sequence.bindings) {
    if (!sequencer::isEntityTarget(b.entity)) continue;
    const Entity* e = state.find(b.entity);
    auto drop = [&](const sequencer::Track& t) {
      const std::string& p = sequencer::trackProperty(t);
      if (!isEmitterTrack(p)) return false;
      std::string why;
      if (const std::optional<std::string> key = emitterTrackKey(p, &why)) {
        const bool vector = particles::spawnValueCount(*key) == 3;
        if (vector ? !std::holds_alternative<sequencer::VectorTrack>(t)
                   : !std::holds_alternative<sequencer::ScalarTrack>(t))
          why = "a track of the wrong kind";
        else if (!e || !e->particles)
          why = "the entity has no particle emitter";
        else
          return false;
      }
      if (warnings)
        warnings->push_back("entity " + std::to_string(b.entity) + " '" + (e ? e->name : b.label) + "' track " + p +
                            ": " + why + "; dropped");
      return true;
    };
    b.tracks.erase(std::remove_if(b.tracks.begin(), b.tracks.end(), drop), b.tracks.end());
  }
}

}  // namespace hs::scene
