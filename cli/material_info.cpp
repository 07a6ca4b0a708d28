#include "cli/material_info.h"

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "scene/fields.h"

namespace hs::cli {
namespace {

// The mesh slots that draw with `id`, as (asset name, slot) pairs.
std::vector<std::pair<std::string, size_t>> slotsUsing(const scene::SceneState& s, scene::MaterialId id) {
  std::vector<std::pair<std::string, size_t>> out;
  for (const auto& [aid, a] : s.assets)
    for (size_t slot = 0; slot < a.materialSlots.size(); ++slot)
      if (a.materialSlots[slot] == id) out.emplace_back(a.name, slot);
  return out;
}

}  // namespace

Json materialInfoJson(const scene::SceneState& s, const scene::Material& m) {
  Json o = Json::object();
  o["name"] = m.name;
  const scene::MeshAsset* a = s.findAsset(m.asset);
  o["asset"] = a ? Json(a->name) : Json(nullptr);
  o["id"] = m.id;
  Json used = Json::array();
  for (const auto& [asset, slot] : slotsUsing(s, m.id)) used.push_back({{"asset", asset}, {"slot", slot}});
  o["used_by"] = std::move(used);
  for (const auto& f : scene::materialFields()) {
    if (f.key == "name") continue;
    const scene::FieldValue v = f.get(m);
    switch (f.type) {
      case scene::FieldType::Double: o[f.key] = std::get<double>(v); break;
      case scene::FieldType::Bool: o[f.key] = std::get<bool>(v); break;
      case scene::FieldType::Enum: o[f.key] = scene::formatFieldValue(f.type, v, f.enumNames); break;
      case scene::FieldType::Vec3:
      case scene::FieldType::Color: {
        const glm::dvec3 c = std::get<glm::dvec3>(v);
        o[f.key] = Json::array({c.x, c.y, c.z});
        break;
      }
      case scene::FieldType::String: o[f.key] = std::get<std::string>(v); break;
      case scene::FieldType::AssetRef: o[f.key] = std::get<int64_t>(v); break;  // texture id, 0: none
    }
  }
  return o;
}

Json materialsInfoJson(const scene::SceneState& s) {
  Json list = Json::array();
  for (const auto& [id, m] : s.materials) list.push_back(materialInfoJson(s, m));
  Json o = Json::object();
  o["materials"] = std::move(list);
  return o;
}

void printMaterials(const scene::SceneState& s) {
  for (const auto& [id, m] : s.materials) {
    const scene::MeshAsset* a = s.findAsset(m.asset);
    std::printf("%s%s\n", m.name.c_str(), a ? ("  (mesh asset " + a->name + ")").c_str() : "");
    std::string used;
    for (const auto& [asset, slot] : slotsUsing(s, m.id))
      used += (used.empty() ? "" : ", ") + asset + " slot " + std::to_string(slot);
    std::printf("  used by: %s\n", used.empty() ? "no mesh" : used.c_str());
    for (const auto& f : scene::materialFields()) {
      if (f.key == "name") continue;
      // Materials hold floats: 7 digits show what was set ("0.8", not the
      // float's double expansion); --json keeps every digit.
      std::string value = scene::formatFieldValue(f.type, f.get(m), f.enumNames, 7);
      if (f.type == scene::FieldType::AssetRef) {
        const scene::TextureAsset* t = s.findTexture(scene::TextureId(std::get<int64_t>(f.get(m))));
        value = t ? value + " (" + t->name + ")" : "0 (none)";
      }
      std::printf("  %s: %s\n", f.key.c_str(), value.c_str());
    }
  }
}

}  // namespace hs::cli
