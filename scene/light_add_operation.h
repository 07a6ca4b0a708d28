#pragma once
// `light add` (hybridscape-cli light add SCENE --type spot ...): a light of
// a type with its fields, added through scene::ops::addLight (undoable, as
// the editor's Create menu adds one). Declared here so the CLI's options,
// help and range messages come from one place (core/params.h).
#include <optional>
#include <string>

#include "core/params.h"
#include "scene/components.h"
#include "scene/transform.h"

namespace hs::scene {

const OperationDecl& lightAddOperation();

struct LightAddRequest {
  std::string name;  // empty: "Sun", "Point Light", "Spot Light"
  Transform transform;
  Light light;
};

// The request from checked parameter values (OperationArgs::value per key;
// absent keys take the type's defaults). nullopt with `error` when values
// break a rule between them (the inner cone beyond the outer one).
std::optional<LightAddRequest> lightAddRequest(const Json& values, std::string& error);

}  // namespace hs::scene
