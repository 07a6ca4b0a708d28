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

}  // namespace hs::scene::ops
