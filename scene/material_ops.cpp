#include "scene/material_ops.h"

#include <cmath>
#include <sstream>

#include "scene/edit.h"

namespace hs::scene::ops {
namespace {

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string outOfRange(double v, const MaterialField& f) {
  if (!std::isfinite(v)) return "is not a finite number";
  if (v < f.min || v > f.max)
    return number(v) + " is out of range (" + number(f.min) + " to " + number(f.max) + (f.unit.empty() ? "" : " " + f.unit) + ")";
  return {};
}

}  // namespace

std::string materialValueProblem(const SceneState& state, const Material& material, const MaterialField& field,
                                 const FieldValue& value) {
  std::string what;
  switch (field.type) {
    case FieldType::Double:
      what = outOfRange(std::get<double>(value), field);
      break;
    case FieldType::Color:
    case FieldType::Vec3: {
      const glm::dvec3 c = std::get<glm::dvec3>(value);
      for (int i = 0; i < 3 && what.empty(); ++i) what = outOfRange(c[i], field);
      break;
    }
    case FieldType::AssetRef: {
      const int64_t t = std::get<int64_t>(value);
      if (t < 0 || (t > 0 && !state.findTexture(TextureId(t))))
        what = "no texture " + std::to_string(t) + " in this scene (0 for none)";
      break;
    }
    case FieldType::String: {
      const std::string& n = std::get<std::string>(value);
      if (n.find_first_not_of(" \t") == std::string::npos) what = "a material needs a name";
      else if (const MaterialId other = state.findMaterialByName(n); other != kNoMaterial && other != material.id)
        what = "another material is named '" + n + "'";
      break;
    }
    case FieldType::Enum: {
      const int64_t i = std::get<int64_t>(value);
      if (i < 0 || size_t(i) >= field.enumNames.size()) what = std::to_string(i) + " is not one of its choices";
      break;
    }
    case FieldType::Bool: break;
  }
  return what.empty() ? what : "material '" + material.name + "': " + field.key + ": " + what;
}

bool setMaterialField(Document& doc, MaterialId id, const MaterialField& field, const FieldValue& value,
                      std::string& error, const QString& mergeKey) {
  error.clear();
  const Material* m = doc.state().findMaterial(id);
  if (!m) {
    error = "no material " + std::to_string(id);
    return false;
  }
  error = materialValueProblem(doc.state(), *m, field, value);
  if (!error.empty()) return false;
  Edit e(doc, QString("Set %1 of %2").arg(QString::fromStdString(field.label), QString::fromStdString(m->name)),
         mergeKey);
  field.set(e.material(id), value);
  return e.commit();
}

bool removeMaterial(Document& doc, MaterialId id, std::string& error) {
  error.clear();
  const Material* m = doc.state().findMaterial(id);
  if (!m) {
    error = "no material " + std::to_string(id);
    return false;
  }
  for (const auto& [aid, asset] : doc.state().assets)
    for (size_t slot = 0; slot < asset.materialSlots.size(); ++slot)
      if (asset.materialSlots[slot] == id) {
        error = "material '" + m->name + "' is used by mesh asset '" + asset.name + "' (slot " +
                std::to_string(slot) + "); it goes with the asset";
        return false;
      }
  Edit e(doc, QString("Delete material %1").arg(QString::fromStdString(m->name)));
  e.removeMaterial(id);  // and its tracks (Edit::removeMaterial)
  return e.commit();
}

MaterialId addMaterial(Document& doc, const std::string& name, MaterialId like, std::string& error) {
  error.clear();
  const SceneState& s = doc.state();
  Material m;
  if (like != kNoMaterial) {
    const Material* from = s.findMaterial(like);
    if (!from) {
      error = "no material " + std::to_string(like);
      return kNoMaterial;
    }
    m = *from;
  }
  m.id = kNoMaterial;
  m.asset = kNoAsset;
  m.name = name;
  // The name goes through the same check as renaming one (fields.cpp's "name").
  if (const MaterialField* f = findMaterialField("name")) {
    error = materialValueProblem(s, m, *f, FieldValue(name));
    if (!error.empty()) {
      // "material '<name>': name: ..." names a material that does not exist yet.
      error = "new material: " + error.substr(std::string("material '" + name + "': ").size());
      return kNoMaterial;
    }
  }
  Edit e(doc, QString("Add material %1").arg(QString::fromStdString(name)));
  const MaterialId id = e.addMaterial(std::move(m));
  e.commit();
  return id;
}

bool assignMaterial(Document& doc, AssetId asset, size_t slot, MaterialId material, std::string& error) {
  error.clear();
  const SceneState& s = doc.state();
  const MeshAsset* a = s.findAsset(asset);
  if (!a) {
    error = "no mesh asset " + std::to_string(asset);
    return false;
  }
  if (slot >= a->materialSlots.size()) {
    const size_t n = a->materialSlots.size();
    error = "mesh asset '" + a->name + "' has no material slot " + std::to_string(slot) +
            (n == 0 ? std::string(" (it has none)") : " (slots 0 to " + std::to_string(n - 1) + ")");
    return false;
  }
  const Material* m = s.findMaterial(material);
  if (!m) {
    error = "no material " + std::to_string(material);
    return false;
  }
  if (a->materialSlots[slot] == material) return false;
  Edit e(doc, QString("Assign %1 to %2 slot %3")
                  .arg(QString::fromStdString(m->name), QString::fromStdString(a->name))
                  .arg(slot));
  e.asset(asset).materialSlots[slot] = material;
  return e.commit();
}

}  // namespace hs::scene::ops
