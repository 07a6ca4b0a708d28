#include "sequencer/key_edit.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

namespace hs::sequencer {

namespace {

// Calls f(keys) with the key vector of `property` in `b` (any key type).
template <class F>
bool visitKeys(Binding& b, const std::string& property, F&& f) {
  if (property == kPathProgress) {
    if (!b.path) return false;
    f(b.path->progress.keys);
    return true;
  }
  for (Track& t : b.tracks)
    if (trackProperty(t) == property) {
      std::visit([&](auto& track) { f(track.keys); }, t);
      return true;
    }
  return false;
}

template <class F>
bool visitKeys(const Binding& b, const std::string& property, F&& f) {
  return visitKeys(const_cast<Binding&>(b), property, [&](const auto& keys) { f(keys); });
}

using Group = std::pair<uint64_t, std::string>;

std::map<Group, std::set<size_t>> groupByTrack(const std::vector<KeyRef>& keys) {
  std::map<Group, std::set<size_t>> groups;
  for (const KeyRef& k : keys) groups[{k.entity, k.property}].insert(k.index);
  return groups;
}

// Re-sorts `keys` stably by time after some moved; a moved key that lands on
// an unmoved key's time replaces it (as Blender's transform does). Returns
// the new indices of the moved keys.
template <class K>
std::vector<size_t> resortMoved(std::vector<K>& keys, const std::set<size_t>& moved) {
  struct Item {
    K key;
    bool moved;
  };
  std::vector<Item> items;
  items.reserve(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) items.push_back({keys[i], moved.count(i) > 0});
  std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.key.time < b.key.time; });
  std::vector<Item> kept;
  for (const Item& it : items) {
    const bool hidden = !it.moved && std::any_of(items.begin(), items.end(), [&](const Item& o) {
      return o.moved && sameKeyTime(o.key.time, it.key.time);
    });
    if (!hidden) kept.push_back(it);
  }
  keys.clear();
  std::vector<size_t> out;
  for (size_t i = 0; i < kept.size(); ++i) {
    keys.push_back(kept[i].key);
    if (kept[i].moved) out.push_back(i);
  }
  return out;
}

std::vector<KeyRef> moveImpl(Sequence& seq, const std::vector<KeyRef>& refs, const std::function<double(double)>& to) {
  std::vector<KeyRef> out;
  // Named references, not a structured binding: the lambdas below capture
  // them, which clang before 16 does not allow for bindings.
  for (const auto& byTrack : groupByTrack(refs)) {
    const auto& group = byTrack.first;
    const auto& indices = byTrack.second;
    Binding* b = seq.findBinding(group.first);
    if (!b) continue;
    visitKeys(*b, group.second, [&](auto& keys) {
      std::set<size_t> valid;
      for (size_t i : indices)
        if (i < keys.size()) {
          keys[i].time = to(keys[i].time);
          valid.insert(i);
        }
      for (size_t i : resortMoved(keys, valid)) out.push_back({group.first, group.second, i});
    });
  }
  std::sort(out.begin(), out.end());
  return out;
}

Track emptyLike(const Track& t) {
  return std::visit(
      [](const auto& track) -> Track {
        auto copy = track;
        copy.keys.clear();
        return copy;
      },
      t);
}

}  // namespace

bool sameKeyTime(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a)); }

std::vector<std::string> trackProperties(const Binding& binding) {
  std::vector<std::string> out;
  for (const Track& t : binding.tracks) out.push_back(trackProperty(t));
  if (binding.path) out.push_back(kPathProgress);
  return out;
}

std::vector<double> keyTimes(const Sequence& sequence, uint64_t entity, const std::string& property) {
  std::vector<double> out;
  if (const Binding* b = sequence.findBinding(entity))
    visitKeys(*b, property, [&](const auto& keys) {
      for (const auto& k : keys) out.push_back(k.time);
    });
  return out;
}

std::vector<KeyRef> allKeys(const Sequence& sequence) {
  std::vector<KeyRef> out;
  for (const Binding& b : sequence.bindings)
    for (const std::string& p : trackProperties(b)) {
      const size_t n = keyTimes(sequence, b.entity, p).size();
      for (size_t i = 0; i < n; ++i) out.push_back({b.entity, p, i});
    }
  return out;
}

std::optional<double> keyTime(const Sequence& sequence, const KeyRef& key) {
  const std::vector<double> t = keyTimes(sequence, key.entity, key.property);
  if (key.index >= t.size()) return std::nullopt;
  return t[key.index];
}

bool keyExists(const Sequence& sequence, const KeyRef& key) { return keyTime(sequence, key).has_value(); }

std::vector<KeyRef> moveKeys(Sequence& sequence, const std::vector<KeyRef>& keys, double dt) {
  return moveImpl(sequence, keys, [dt](double t) { return t + dt; });
}

std::vector<KeyRef> moveKeysSnapped(Sequence& sequence, const std::vector<KeyRef>& keys, double dt, FrameRate rate) {
  return moveImpl(sequence, keys, [dt, rate](double t) { return frameTime(frameAtTime(t + dt, rate), rate); });
}

size_t removeKeys(Sequence& sequence, const std::vector<KeyRef>& keys) {
  size_t removed = 0;
  // Named references, not a structured binding: the lambdas below capture
  // them, which clang before 16 does not allow for bindings.
  for (const auto& byTrack : groupByTrack(keys)) {
    const auto& group = byTrack.first;
    const auto& indices = byTrack.second;
    Binding* b = sequence.findBinding(group.first);
    if (!b) continue;
    visitKeys(*b, group.second, [&](auto& k) {
      for (auto it = indices.rbegin(); it != indices.rend(); ++it)
        if (*it < k.size()) {
          k.erase(k.begin() + std::ptrdiff_t(*it));
          ++removed;
        }
    });
    std::erase_if(b->tracks, [](const Track& t) { return trackKeyCount(t) == 0; });
  }
  std::erase_if(sequence.bindings, [](const Binding& b) { return b.tracks.empty() && !b.path; });
  return removed;
}

KeyClipboard copyKeys(const Sequence& sequence, const std::vector<KeyRef>& keys) {
  KeyClipboard clip;
  double earliest = INFINITY;
  for (const KeyRef& k : keys)
    if (auto t = keyTime(sequence, k)) earliest = std::min(earliest, *t);
  // Named references, not a structured binding: the lambdas below capture
  // them, which clang before 16 does not allow for bindings.
  for (const auto& byTrack : groupByTrack(keys)) {
    const auto& group = byTrack.first;
    const auto& indices = byTrack.second;
    const Binding* b = sequence.findBinding(group.first);
    if (!b) continue;
    KeyClipboard::Entry entry{group.first, b->label, group.second, {}};
    bool found = false;
    if (group.second == kPathProgress) {
      if (!b->path) continue;
      ScalarTrack t{kPathProgress, {}};
      for (size_t i : indices)
        if (i < b->path->progress.keys.size()) t.keys.push_back(b->path->progress.keys[i]);
      entry.keys = t;
      found = !t.keys.empty();
    } else {
      for (const Track& t : b->tracks)
        if (trackProperty(t) == group.second) {
          entry.keys = emptyLike(t);
          std::visit(
              [&](auto& dst) {
                const auto& src = std::get<std::decay_t<decltype(dst)>>(t);
                for (size_t i : indices)
                  if (i < src.keys.size()) dst.keys.push_back(src.keys[i]);
                found = !dst.keys.empty();
              },
              entry.keys);
        }
    }
    if (!found) continue;
    std::visit([&](auto& track) {
      for (auto& k : track.keys) k.time -= earliest;
    }, entry.keys);
    clip.entries.push_back(std::move(entry));
  }
  return clip;
}

std::vector<KeyRef> pasteKeys(Sequence& sequence, const KeyClipboard& clipboard, double t) {
  std::vector<std::pair<Group, double>> pasted;  // (track, time) to find indices afterwards
  for (const KeyClipboard::Entry& e : clipboard.entries) {
    Binding* b = sequence.findBinding(e.entity);
    if (!b) {
      if (e.property == kPathProgress) continue;
      sequence.bindings.push_back(Binding{e.entity, e.label, {}, std::nullopt});
      b = &sequence.bindings.back();
    }
    if (e.property != kPathProgress &&
        std::none_of(b->tracks.begin(), b->tracks.end(), [&](const Track& x) { return trackProperty(x) == e.property; }))
      b->tracks.push_back(emptyLike(e.keys));
    std::visit(
        [&](const auto& src) {
          visitKeys(*b, e.property, [&](auto& dst) {
            using DstKey = typename std::decay_t<decltype(dst)>::value_type;
            using SrcKey = typename std::decay_t<decltype(src.keys)>::value_type;
            if constexpr (std::is_same_v<DstKey, SrcKey>) {
              for (SrcKey k : src.keys) {
                k.time += t;
                std::erase_if(dst, [&](const DstKey& d) { return sameKeyTime(d.time, k.time); });
                dst.push_back(k);
                pasted.push_back({{e.entity, e.property}, k.time});
              }
              std::stable_sort(dst.begin(), dst.end(), [](const DstKey& a, const DstKey& c) { return a.time < c.time; });
            }
          });
        },
        e.keys);
  }
  std::vector<KeyRef> out;
  for (const auto& [group, time] : pasted) {
    const std::vector<double> times = keyTimes(sequence, group.first, group.second);
    for (size_t i = 0; i < times.size(); ++i)
      if (times[i] == time) out.push_back({group.first, group.second, i});
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

double comp(double v, int) { return v; }
double comp(const glm::dvec3& v, int c) { return v[c]; }
void setComp(double& v, int, double x) { v = x; }
void setComp(glm::dvec3& v, int c, double x) { v[c] = x; }

// The curve's slope of one component just before (in) and after (out) time t.
template <class TrackT>
std::pair<double, double> numericSlopes(const TrackT& track, double t, int c) {
  const double eps = 1e-6 * std::max(1.0, std::abs(t));
  const auto v0 = evaluate(track, t), vm = evaluate(track, t - eps), vp = evaluate(track, t + eps);
  if (!v0 || !vm || !vp) return {0.0, 0.0};
  return {(comp(*v0, c) - comp(*vm, c)) / eps, (comp(*vp, c) - comp(*v0, c)) / eps};
}

// Calls f(track, keyIndex) for a scalar or vector track's key (a path's
// progress is a scalar track); false for other kinds or stale references.
template <class F>
bool withCurveKey(Sequence& seq, const KeyRef& key, F&& f) {
  Binding* b = seq.findBinding(key.entity);
  if (!b) return false;
  if (key.property == kPathProgress) {
    if (!b->path || key.index >= b->path->progress.keys.size()) return false;
    f(b->path->progress, key.index);
    return true;
  }
  for (Track& t : b->tracks) {
    if (trackProperty(t) != key.property) continue;
    if (auto* s = std::get_if<ScalarTrack>(&t); s && key.index < s->keys.size()) return f(*s, key.index), true;
    if (auto* v = std::get_if<VectorTrack>(&t); v && key.index < v->keys.size()) return f(*v, key.index), true;
    return false;
  }
  return false;
}

template <class TrackT>
constexpr int componentsOf() {
  return std::is_same_v<TrackT, VectorTrack> ? 3 : 1;
}

}  // namespace

size_t setKeyShape(Sequence& sequence, const std::vector<KeyRef>& keys, const KeyShape& shape) {
  size_t changed = 0;
  // Slopes are read from the curve as it is before any key changes.
  const Sequence before = sequence;
  for (const KeyRef& k : keys) {
    Binding* b = sequence.findBinding(k.entity);
    if (!b) continue;
    const bool curve = withCurveKey(sequence, k, [&](auto& track, size_t i) {
      using TrackT = std::decay_t<decltype(track)>;
      auto& key = track.keys[i];
      if (shape.interpolation) key.interpolation = *shape.interpolation;
      if (shape.ease) key.ease = *shape.ease;
      if (shape.tangent) {
        if (key.tangentMode == TangentMode::Auto && *shape.tangent != TangentMode::Auto) {
          TrackT old = track;
          withCurveKey(const_cast<Sequence&>(before), k, [&](auto& t0, size_t) {
            if constexpr (std::is_same_v<std::decay_t<decltype(t0)>, TrackT>) old = t0;
          });
          for (int c = 0; c < componentsOf<TrackT>(); ++c) {
            const auto [in, out] = numericSlopes(old, key.time, c);
            setComp(key.inSlope, c, *shape.tangent == TangentMode::User ? out : in);
            setComp(key.outSlope, c, out);
          }
        }
        if (*shape.tangent == TangentMode::User) key.inSlope = key.outSlope;
        key.tangentMode = *shape.tangent;
      }
      ++changed;
    });
    if (curve) continue;
    visitKeys(*b, k.property, [&](auto& v) {
      using K = typename std::decay_t<decltype(v)>::value_type;
      if constexpr (!std::is_same_v<K, StepKey>) {
        if (k.index >= v.size()) return;
        if (shape.interpolation) v[k.index].interpolation = *shape.interpolation;
        if (shape.ease) v[k.index].ease = *shape.ease;
        if (shape.tangent) v[k.index].tangentMode = *shape.tangent;
        ++changed;
      }
    });
  }
  return changed;
}

std::optional<double> keyComponent(const Sequence& sequence, const KeyRef& key, int component) {
  std::optional<double> out;
  withCurveKey(const_cast<Sequence&>(sequence), key, [&](auto& track, size_t i) {
    if (component < componentsOf<std::decay_t<decltype(track)>>()) out = comp(track.keys[i].value, component);
  });
  return out;
}

bool setKeyComponent(Sequence& sequence, const KeyRef& key, int component, double value) {
  bool ok = false;
  withCurveKey(sequence, key, [&](auto& track, size_t i) {
    if (component >= componentsOf<std::decay_t<decltype(track)>>() || !std::isfinite(value)) return;
    setComp(track.keys[i].value, component, value);
    ok = true;
  });
  return ok;
}

std::optional<std::pair<double, double>> keySlopes(const Sequence& sequence, const KeyRef& key, int component) {
  std::optional<std::pair<double, double>> out;
  withCurveKey(const_cast<Sequence&>(sequence), key, [&](auto& track, size_t i) {
    if (component >= componentsOf<std::decay_t<decltype(track)>>()) return;
    const auto& k = track.keys[i];
    switch (k.tangentMode) {
      case TangentMode::Auto: out = numericSlopes(track, k.time, component); break;
      case TangentMode::User: out = std::pair{comp(k.outSlope, component), comp(k.outSlope, component)}; break;
      case TangentMode::Broken: out = std::pair{comp(k.inSlope, component), comp(k.outSlope, component)}; break;
    }
  });
  return out;
}

bool setKeySlope(Sequence& sequence, const KeyRef& key, int component, std::optional<double> in,
                 std::optional<double> out, bool broken) {
  bool ok = false;
  withCurveKey(sequence, key, [&](auto& track, size_t i) {
    using TrackT = std::decay_t<decltype(track)>;
    if (component >= componentsOf<TrackT>()) return;
    auto& k = track.keys[i];
    if (k.tangentMode == TangentMode::Auto) {
      // Keep the other components' current shape when leaving Auto.
      for (int c = 0; c < componentsOf<TrackT>(); ++c) {
        const auto [si, so] = numericSlopes(track, k.time, c);
        setComp(k.inSlope, c, si);
        setComp(k.outSlope, c, so);
      }
      k.tangentMode = TangentMode::User;
    }
    if (broken) k.tangentMode = TangentMode::Broken;
    if (k.tangentMode == TangentMode::User) {
      const double s = out ? *out : in ? *in : comp(k.outSlope, component);
      setComp(k.outSlope, component, s);
      k.inSlope = k.outSlope;
    } else {
      if (in) setComp(k.inSlope, component, *in);
      if (out) setComp(k.outSlope, component, *out);
    }
    ok = true;
  });
  return ok;
}

}  // namespace hs::sequencer
