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

bool emitterKeyIsVector(std::string_view key) { return key == "direction" || key == "box_half_m"; }

std::optional<sequencer::PropertyValue> emitterKeyValue(const particles::EmitterDesc& d, std::string_view key) {
  if (!particles::isSpawnKey(key)) return std::nullopt;
  const particles::SpawnValues v = particles::spawnValues(d);
  if (key == "direction") return sequencer::PropertyValue(v.direction);
  if (key == "box_half_m") return sequencer::PropertyValue(v.boxHalf);
  if (key == "speed_m_per_s") return sequencer::PropertyValue(0.5 * (v.speedMin + v.speedMax));
  if (key == "size_m") return sequencer::PropertyValue(0.5 * (v.sizeMin + v.sizeMax));
  if (key == "rotation_deg") return sequencer::PropertyValue(0.5 * (v.rotationMinDeg + v.rotationMaxDeg));
  if (key == "spin_deg_per_s") return sequencer::PropertyValue(0.5 * (v.spinMinDegPerS + v.spinMaxDegPerS));
  if (key == "spread_deg") return sequencer::PropertyValue(v.spreadDeg);
  if (key == "cone_angle_deg") return sequencer::PropertyValue(v.coneAngleDeg);
  if (key == "radius_m") return sequencer::PropertyValue(v.radius);
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
  const bool vector = emitterKeyIsVector(key);
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
  for (const sequencer::Track& t : b->tracks)
    if (emitterTrackKey(sequencer::trackProperty(t)) && sequencer::trackKeyCount(t) > 0) out->tracks_.push_back(t);
  if (out->tracks_.empty()) return nullptr;
  return out;
}

void EmitterSpawnTracks::apply(double birth, particles::SpawnValues& v) const {
  for (const sequencer::Track& t : tracks_) {
    const std::string key = sequencer::trackProperty(t).substr(kEmitterTrackPrefix.size());
    if (const auto* s = std::get_if<sequencer::ScalarTrack>(&t)) {
      if (const std::optional<double> x = sequencer::evaluate(*s, birth)) particles::setSpawnValue(v, key, &*x, 1);
    } else if (const auto* w = std::get_if<sequencer::VectorTrack>(&t)) {
      if (const std::optional<glm::dvec3> x = sequencer::evaluate(*w, birth)) {
        const double xyz[3] = {x->x, x->y, x->z};
        particles::setSpawnValue(v, key, xyz, 3);
      }
    }
  }
}

void checkEmitterTracks(SceneState& state, std::vector<std::string>* warnings) {
  for (sequencer::Binding& b : state.sequence.bindings) {
    if (!sequencer::isEntityTarget(b.entity)) continue;
    const Entity* e = state.find(b.entity);
    auto drop = [&](const sequencer::Track& t) {
      const std::string& p = sequencer::trackProperty(t);
      if (!isEmitterTrack(p)) return false;
      std::string why;
      const bool kindFits = emitterTrackKey(p) &&
                            (emitterKeyIsVector(p.substr(kEmitterTrackPrefix.size()))
                                 ? std::holds_alternative<sequencer::VectorTrack>(t)
                                 : std::holds_alternative<sequencer::ScalarTrack>(t));
      if (!emitterTrackKey(p, &why)) {
      } else if (!kindFits) {
        why = "a track of the wrong kind";
      } else if (!e || !e->particles) {
        why = "the entity has no particle emitter";
      } else {
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
