#pragma once
// Edits of keys inside a Sequence value: find, retime, remove, copy and
// paste keys named by (entity, property, index). Pure functions on plain
// data, so the editor's timeline, the CLI and tests share them, and scene/
// wraps each in one undoable edit. A camera path's progress track is
// addressed as the property "path.progress" of its binding.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sequencer/sequence.h"

namespace hs::sequencer {

inline constexpr const char* kPathProgress = "path.progress";

// A key of a sequence: the binding's entity, the track's property and the
// key's index in that track (keys are kept sorted by time).
struct KeyRef {
  uint64_t entity = 0;
  std::string property;
  size_t index = 0;
  auto operator<=>(const KeyRef&) const = default;
};

// The tracks of a binding as the timeline lists them: its tracks in order,
// then "path.progress" when it follows a path.
std::vector<std::string> trackProperties(const Binding& binding);
// Times of the keys of one track (empty if there is no such track).
std::vector<double> keyTimes(const Sequence& sequence, uint64_t entity, const std::string& property);
// Every key of the sequence.
std::vector<KeyRef> allKeys(const Sequence& sequence);
// The key's time, or nullopt if the reference is stale.
std::optional<double> keyTime(const Sequence& sequence, const KeyRef& key);
bool keyExists(const Sequence& sequence, const KeyRef& key);

// Moves `keys` by `dt` seconds (a drag in the timeline: callers pass the
// sequence as it was when the drag started and the total offset, so a drag
// never accumulates rounding). Keys are re-sorted stably; the result names
// the moved keys at their new indices. Stale references are ignored.
std::vector<KeyRef> moveKeys(Sequence& sequence, const std::vector<KeyRef>& keys, double dt);
// Like moveKeys, but with times snapped to the nearest frame of the rate.
std::vector<KeyRef> moveKeysSnapped(Sequence& sequence, const std::vector<KeyRef>& keys, double dt, FrameRate rate);

// Removes the keys; a track left without keys is removed, and a binding
// left without tracks or path too. Returns how many keys went.
size_t removeKeys(Sequence& sequence, const std::vector<KeyRef>& keys);

// Copied keys, with times relative to the earliest of them.
struct KeyClipboard {
  struct Entry {
    uint64_t entity = 0;
    std::string label;
    std::string property;
    Track keys;  // same track type as the source, only the copied keys; for path.progress a ScalarTrack
  };
  std::vector<Entry> entries;
  bool empty() const { return entries.empty(); }
};
KeyClipboard copyKeys(const Sequence& sequence, const std::vector<KeyRef>& keys);
// Pastes at time `t` (the earliest copied key lands there) onto the same
// entities and properties; a key already at a pasted time is replaced.
// Entries whose entity has no binding get one (label from the clipboard);
// "path.progress" entries need the binding to still have its path. Returns
// the pasted keys.
std::vector<KeyRef> pasteKeys(Sequence& sequence, const KeyClipboard& clipboard, double t);

// How keys shape their segments (the parts left unset are kept). Keys of
// on/off tracks only step and are left alone. Switching a key from Auto to
// User or Broken tangents keeps the curve's shape: the slopes it had are
// written into the key (scalar and vector tracks).
struct KeyShape {
  std::optional<Interpolation> interpolation;
  std::optional<TangentMode> tangent;
  std::optional<Ease> ease;
};
size_t setKeyShape(Sequence& sequence, const std::vector<KeyRef>& keys, const KeyShape& shape);

// A key's value in a curve: component 0-2 of a vector key, 0 of a scalar
// key (a camera path's progress included). nullopt for rotation and on/off keys.
std::optional<double> keyComponent(const Sequence& sequence, const KeyRef& key, int component);
bool setKeyComponent(Sequence& sequence, const KeyRef& key, int component, double value);
// Slopes (units per second) of one component as the curve leaves and
// arrives at the key: the stored ones for User/Broken keys, the computed
// ones for Auto keys.
std::optional<std::pair<double, double>> keySlopes(const Sequence& sequence, const KeyRef& key, int component);
// Sets the arriving and/or leaving slope of one component. A key with Auto
// tangents becomes User (one slope both sides: setting either sets both)
// unless `broken`, which makes the two sides independent.
bool setKeySlope(Sequence& sequence, const KeyRef& key, int component, std::optional<double> in,
                 std::optional<double> out, bool broken);

// True if two times name the same key slot (within 1e-9 s, relative for
// large times): setting a key there replaces the existing one.
bool sameKeyTime(double a, double b);

}  // namespace hs::sequencer
