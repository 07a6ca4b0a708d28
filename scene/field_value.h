#pragma once
// A value of one editable field (scene/fields.h): what the property panel,
// `hybridscape-cli set`, files and animation keys exchange. Its own header
// so components can hold values of fields (a camera's post settings,
// scene/camera_post.h) without the field tables.
#include <cstdint>
#include <string>
#include <variant>

#include <glm/glm.hpp>

namespace hs::scene {

// double (Double), bool (Bool), int64 (Enum index, AssetRef id), dvec3
// (Vec3, Color), string (String): FieldType in fields.h.
using FieldValue = std::variant<double, bool, int64_t, glm::dvec3, std::string>;

}  // namespace hs::scene
