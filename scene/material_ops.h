#pragma once
// Undoable edits of materials (scene/material.h), for the Materials panel,
// `hybridscape-cli material set` and tests. A value is checked against its
// field's declaration (fields.cpp) and refused with a message that names
// the material and the field; the document is then unchanged.
#include <string>

#include <QString>

#include "scene/document.h"
#include "scene/fields.h"

namespace hs::scene::ops {

// What is wrong with `value` for `field` of `material` ("" if nothing):
// NaN or out of the declared range, a texture the scene does not have, an
// empty or taken name. The message names both:
//   material 'Rock / bark': opacity: 1.5 is out of range (0 to 1)
std::string materialValueProblem(const SceneState& state, const Material& material, const MaterialField& field,
                                 const FieldValue& value);

// Sets one field in one undo step. False with `error` when refused (or
// with `error` empty when the value was already that).
bool setMaterialField(Document& doc, MaterialId id, const MaterialField& field, const FieldValue& value,
                      std::string& error, const QString& mergeKey = {});

// Deletes a material in one undo step, with its timeline tracks
// (object_tracks.h; undo brings both back). A material a mesh asset's slot
// still draws with is refused with `error` naming the asset.
bool removeMaterial(Document& doc, MaterialId id, std::string& error);

// Adds a material named `name` in one undo step: a copy of `like`'s fields
// (kNoMaterial: the defaults of scene/material.h), owned by the scene, not
// by a mesh asset (it stays when an asset goes). Returns its id, or
// kNoMaterial with `error` (an empty or taken name, an unknown `like`).
MaterialId addMaterial(Document& doc, const std::string& name, MaterialId like, std::string& error);

// Makes slot `slot` of mesh asset `asset` draw with material `material`, in
// one undo step (every entity showing the asset follows, as in the file).
// False with `error` naming the asset, slot or material when refused, or
// with `error` empty when the slot already had it.
bool assignMaterial(Document& doc, AssetId asset, size_t slot, MaterialId material, std::string& error);

}  // namespace hs::scene::ops
