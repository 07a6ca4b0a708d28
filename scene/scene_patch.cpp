#include "scene/scene_patch.h"

namespace hs::scene {
namespace {

template <class Id, class T>
void mergeLaterMap(std::map<Id, BeforeAfter<T>>& into, const std::map<Id, BeforeAfter<T>>& later) {
  for (const auto& [id, ba] : later) {
    auto it = into.find(id);
    if (it == into.end())
      into.emplace(id, ba);
    else
      it->second.after = ba.after;
  }
}

template <class Id, class T>
void applyMap(std::map<Id, T>& state, const std::map<Id, BeforeAfter<T>>& patch, bool forward) {
  for (const auto& [id, ba] : patch) {
    const auto& value = forward ? ba.after : ba.before;
    if (value)
      state[id] = *value;
    else
      state.erase(id);
  }
}

}  // namespace

void ScenePatch::mergeLater(const ScenePatch& later) {
  for (const auto& [id, ba] : later.entities) {
    auto it = entities.find(id);
    if (it == entities.end())
      entities.emplace(id, ba);
    else
      it->second.after = ba.after;
  }
  if (later.roots) {
    if (roots)
      roots->second = later.roots->second;
    else
      roots = later.roots;
  }
  for (const auto& [id, ba] : later.assets) {
    auto it = assets.find(id);
    if (it == assets.end())
      assets.emplace(id, ba);
    else
      it->second.after = ba.after;
  }
  for (const auto& [id, ba] : later.terrains) {
    auto it = terrains.find(id);
    if (it == terrains.end())
      terrains.emplace(id, ba);
    else
      it->second.after = ba.after;
  }
  mergeLaterMap(materials, later.materials);
  mergeLaterMap(textures, later.textures);
  if (later.settings) {
    if (settings)
      settings->second = later.settings->second;
    else
      settings = later.settings;
  }
  if (later.sequence) {
    if (sequence)
      sequence->second = later.sequence->second;
    else
      sequence = later.sequence;
  }
}

void ScenePatch::prune() {
  std::erase_if(entities, [](const auto& kv) { return kv.second.before == kv.second.after; });
  std::erase_if(assets, [](const auto& kv) { return kv.second.before == kv.second.after; });
  std::erase_if(terrains, [](const auto& kv) { return kv.second.before == kv.second.after; });
  std::erase_if(materials, [](const auto& kv) { return kv.second.before == kv.second.after; });
  std::erase_if(textures, [](const auto& kv) { return kv.second.before == kv.second.after; });
  if (roots && roots->first == roots->second) roots.reset();
  if (settings && settings->first == settings->second) settings.reset();
  if (sequence && sequence->first == sequence->second) sequence.reset();
}

void applyPatch(SceneState& state, const ScenePatch& patch, bool forward) {
  for (const auto& [id, ba] : patch.entities) {
    const auto& value = forward ? ba.after : ba.before;
    if (value)
      state.entities[id] = *value;
    else
      state.entities.erase(id);
  }
  if (patch.roots) state.roots = forward ? patch.roots->second : patch.roots->first;
  for (const auto& [id, ba] : patch.assets) {
    const auto& value = forward ? ba.after : ba.before;
    if (value)
      state.assets[id] = *value;
    else
      state.assets.erase(id);
  }
  for (const auto& [id, ba] : patch.terrains) {
    const auto& value = forward ? ba.after : ba.before;
    if (value)
      state.terrains[id] = *value;
    else
      state.terrains.erase(id);
  }
  applyMap(state.materials, patch.materials, forward);
  applyMap(state.textures, patch.textures, forward);
  if (patch.settings) state.settings = forward ? patch.settings->second : patch.settings->first;
  if (patch.sequence) state.sequence = forward ? patch.sequence->second : patch.sequence->first;
}

}  // namespace hs::scene
