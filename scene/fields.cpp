#include "scene/fields.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <utility>

#include "scene/camera_post.h"
#include "scene/ocio_config.h"

namespace hs::scene {
namespace {

double clampFinite(double v, double lo, double hi, double fallback) {
  if (!std::isfinite(v)) return fallback;
  return std::clamp(v, lo, hi);
}

// Builders for the common field shapes. `Member` is a pointer-to-member
// getter returning a reference, so one lambda serves get and set.
template <class Target, class Access>
FieldInfo<Target> doubleField(std::string key, std::string label, double min, double max,
                              double step, std::string unit, Access access) {
  FieldInfo<Target> f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::Double;
  f.min = min;
  f.max = max;
  f.step = step;
  f.unit = std::move(unit);
  f.get = [access](const Target& t) {
    return FieldValue(double(access(const_cast<Target&>(t))));
  };
  f.set = [access, min, max](Target& t, const FieldValue& v) {
    auto& ref = access(t);
    using T = std::remove_reference_t<decltype(ref)>;
    const double held = clampFinite(std::get<double>(v), min, max, double(ref));
    if constexpr (std::is_integral_v<T>) ref = T(std::llround(held));  // 4.6 steps: 5, not 4
    else ref = T(held);
  };
  // A whole-number field (an int behind it) says when it rounds. Set here,
  // before any caller's own check: none of those fields has one.
  using Held = std::remove_reference_t<decltype(access(std::declval<Target&>()))>;
  if constexpr (std::is_integral_v<Held>) {
    f.check = [](const FieldValue& v, const Target*) {
      const double d = std::get<double>(v);
      return std::isfinite(d) && d != std::round(d) ? std::string("must be a whole number") : std::string();
    };
  }
  return f;
}

template <class Target, class Access>
FieldInfo<Target> stringField(std::string key, std::string label, Access access) {
  FieldInfo<Target> f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::String;
  f.animatable = false;  // a name: no value between two keys
  f.get = [access](const Target& t) { return FieldValue(std::string(access(const_cast<Target&>(t)))); };
  f.set = [access](Target& t, const FieldValue& v) { access(t) = std::get<std::string>(v); };
  return f;
}

template <class Target, class Access>
FieldInfo<Target> boolField(std::string key, std::string label, Access access) {
  FieldInfo<Target> f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::Bool;
  f.get = [access](const Target& t) { return FieldValue(bool(access(const_cast<Target&>(t)))); };
  f.set = [access](Target& t, const FieldValue& v) { access(t) = std::get<bool>(v); };
  return f;
}

template <class Target, class Access>
FieldInfo<Target> colorField(std::string key, std::string label, Access access) {
  FieldInfo<Target> f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::Color;
  f.min = 0.0;
  f.max = 1000.0;  // HDR colours are allowed; negative ones are not
  f.get = [access](const Target& t) {
    return FieldValue(glm::dvec3(access(const_cast<Target&>(t))));
  };
  f.set = [access](Target& t, const FieldValue& v) {
    auto& ref = access(t);
    const glm::dvec3 c = std::get<glm::dvec3>(v);
    for (int i = 0; i < 3; ++i) ref[i] = float(clampFinite(c[i], 0.0, 1000.0, double(ref[i])));
  };
  return f;
}

template <class Target, class Access>
FieldInfo<Target> enumField(std::string key, std::string label, std::vector<std::string> names,
                            Access access) {
  FieldInfo<Target> f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::Enum;
  f.min = 0;
  f.max = double(names.size() - 1);
  f.enumNames = std::move(names);
  f.animatable = false;
  const int64_t count = int64_t(f.enumNames.size());
  f.get = [access](const Target& t) {
    return FieldValue(int64_t(access(const_cast<Target&>(t))));
  };
  f.set = [access, count](Target& t, const FieldValue& v) {
    auto& ref = access(t);
    using T = std::remove_reference_t<decltype(ref)>;
    ref = T(std::clamp<int64_t>(std::get<int64_t>(v), 0, count - 1));
  };
  return f;
}

// Three numbers in [min, max] each (a grade's lift, gamma or gain per channel).
template <class Target, class Access>
FieldInfo<Target> boundedVec3Field(std::string key, std::string label, double min, double max, Access access) {
  FieldInfo<Target> f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::Vec3;
  f.min = min;
  f.max = max;
  f.step = 0.01;
  f.get = [access](const Target& t) { return FieldValue(glm::dvec3(access(const_cast<Target&>(t)))); };
  f.set = [access, min, max](Target& t, const FieldValue& v) {
    auto& ref = access(t);
    const glm::dvec3 c = std::get<glm::dvec3>(v);
    for (int i = 0; i < 3; ++i) ref[i] = float(clampFinite(c[i], min, max, double(ref[i])));
  };
  return f;
}

EntityField vec3Field(std::string key, std::string label, std::string unit, double step,
                      std::function<glm::dvec3(const Entity&)> get,
                      std::function<void(Entity&, glm::dvec3)> set) {
  EntityField f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::Vec3;
  f.step = step;
  f.unit = std::move(unit);
  f.get = [get](const Entity& e) { return FieldValue(get(e)); };
  f.set = [get, set](Entity& e, const FieldValue& v) {
    glm::dvec3 x = std::get<glm::dvec3>(v);
    const glm::dvec3 old = get(e);
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(x[i])) x[i] = old[i];  // NaN from a script never enters the document
    set(e, x);
  };
  return f;
}

// Focal length on a full-frame sensor, derived from the field of view: the
// same value seen the way photographers set it.
EntityField focalLengthField() {
  EntityField f;
  f.key = "focal_length_mm";
  f.label = "Focal length";
  f.type = FieldType::Double;
  f.min = 1.0;
  f.max = 5000.0;
  f.step = 1.0;
  f.unit = "mm";
  f.serialized = false;
  f.get = [](const Entity& e) {
    const double fov = glm::radians(e.camera->verticalFovDeg);
    return FieldValue(kSensorHeightMm / (2.0 * std::tan(fov * 0.5)));
  };
  f.set = [](Entity& e, const FieldValue& v) {
    const double mm = clampFinite(std::get<double>(v), 1.0, 5000.0, 0.0);
    if (mm <= 0.0) return;
    e.camera->verticalFovDeg = std::clamp(glm::degrees(2.0 * std::atan(kSensorHeightMm / (2.0 * mm))), 1.0, 170.0);
  };
  return f;
}

template <class C>
ComponentInfo optionalComponent(std::string key, std::string label,
                                std::optional<C> Entity::*member, std::vector<EntityField> fields) {
  ComponentInfo c;
  c.key = std::move(key);
  c.label = std::move(label);
  c.optional = true;
  c.has = [member](const Entity& e) { return (e.*member).has_value(); };
  c.add = [member](Entity& e) {
    if (!(e.*member)) e.*member = C{};
  };
  c.remove = [member](Entity& e) { (e.*member).reset(); };
  c.fields = std::move(fields);
  return c;
}

std::vector<ComponentInfo> buildEntityComponents() {
  std::vector<ComponentInfo> out;

  ComponentInfo entity;
  entity.key = "entity";
  entity.label = "Entity";
  entity.optional = false;
  entity.has = [](const Entity&) { return true; };
  {
    EntityField name;
    name.key = "name";
    name.label = "Name";
    name.type = FieldType::String;
    name.animatable = false;
    name.get = [](const Entity& e) { return FieldValue(e.name); };
    name.set = [](Entity& e, const FieldValue& v) { e.name = std::get<std::string>(v); };
    name.check = [](const FieldValue& v, const Entity*) {
      return std::get<std::string>(v).empty() ? std::string("must not be empty") : std::string();
    };
    name.repair = [](Entity& e) { e.name = "Entity " + std::to_string(e.id); };
    entity.fields.push_back(name);
    entity.fields.push_back(boolField<Entity>("visible", "Visible", [](Entity& e) -> bool& { return e.visible; }));
  }
  out.push_back(entity);

  ComponentInfo transform;
  transform.key = "transform";
  transform.label = "Transform";
  transform.optional = false;
  transform.has = [](const Entity&) { return true; };
  transform.fields.push_back(vec3Field(
      "translation", "Location", "m", 0.1, [](const Entity& e) { return e.transform.translation; },
      [](Entity& e, glm::dvec3 v) { e.transform.translation = v; }));
  transform.fields.push_back(vec3Field(
      "rotation_deg", "Rotation", "°", 1.0,
      [](const Entity& e) { return eulerDegrees(e.transform.rotation); },
      [](Entity& e, glm::dvec3 v) { e.transform.rotation = fromEulerDegrees(v); }));
  transform.fields.push_back(vec3Field(
      "scale", "Scale", "", 0.01, [](const Entity& e) { return e.transform.scale; },
      [](Entity& e, glm::dvec3 v) {
        // A zero scale makes the matrix singular (no picking, no normals):
        // keep a tiny positive or negative value instead.
        for (int i = 0; i < 3; ++i)
          if (std::abs(v[i]) < 1e-9) v[i] = v[i] < 0 ? -1e-9 : 1e-9;
        e.transform.scale = v;
      }));
  transform.fields.back().check = [](const FieldValue& v, const Entity*) {
    const glm::dvec3 x = std::get<glm::dvec3>(v);
    return x.x == 0.0 || x.y == 0.0 || x.z == 0.0 ? std::string("must be non-zero on every axis")
                                                   : std::string();
  };
  out.push_back(transform);

  {
    EntityField asset;
    asset.key = "asset";
    asset.label = "Mesh asset";
    asset.type = FieldType::AssetRef;
    asset.animatable = false;
    asset.get = [](const Entity& e) { return FieldValue(int64_t(e.mesh ? e.mesh->mesh : 0)); };
    asset.set = [](Entity& e, const FieldValue& v) {
      if (e.mesh) e.mesh->mesh = AssetId(std::max<int64_t>(0, std::get<int64_t>(v)));
    };
    out.push_back(optionalComponent<MeshInstance>(
        "mesh", "Mesh", &Entity::mesh,
        {asset, colorField<Entity>("tint", "Tint", [](Entity& e) -> glm::vec3& { return e.mesh->tint; })}));
  }

  // Physical units (components.h, light_units.h): lux for a sun, lumens
  // for point and spot lights. Cone angles are full apex angles in (0, 180).
  out.push_back(optionalComponent<Light>(
      "light", "Light", &Entity::light,
      {enumField<Entity>("type", "Type", {"Sun", "Point", "Spot"},
                         [](Entity& e) -> Light::Type& { return e.light->type; }),
       colorField<Entity>("color", "Colour", [](Entity& e) -> glm::vec3& { return e.light->color; }),
       doubleField<Entity>("intensity", "Intensity", 0.0, 1e12, 100.0, "lx (sun) or lm",
                           [](Entity& e) -> float& { return e.light->intensity; }),
       doubleField<Entity>("range", "Range", 0.01, 1e7, 1.0, "m",
                           [](Entity& e) -> float& { return e.light->range; }),
       doubleField<Entity>("inner_cone_deg", "Inner cone", 0.1, 179.9, 1.0, "°",
                           [](Entity& e) -> float& { return e.light->innerConeDeg; }),
       doubleField<Entity>("outer_cone_deg", "Outer cone", 0.1, 179.9, 1.0, "°",
                           [](Entity& e) -> float& { return e.light->outerConeDeg; }),
       boolField<Entity>("casts_shadows", "Casts shadows", [](Entity& e) -> bool& { return e.light->castsShadows; }),
       doubleField<Entity>("shadow_resolution", "Shadow resolution (0: from settings)", 0.0, 16384.0, 256.0, "px",
                           [](Entity& e) -> int& { return e.light->shadowResolution; })}));
  // The beam's cones bound each other: the inner one within the outer one.
  for (EntityField& f : out.back().fields) {
    if (f.key == "inner_cone_deg") {
      f.check = [](const FieldValue& v, const Entity* e) {
        return e && e->light && std::get<double>(v) > double(e->light->outerConeDeg)
                   ? "must not exceed the outer cone (" + formatFieldValue(FieldType::Double, double(e->light->outerConeDeg), {}, 6) +
                         " °)"
                   : std::string();
      };
      f.repair = [](Entity& e) { e.light->innerConeDeg = e.light->outerConeDeg; };
    } else if (f.key == "outer_cone_deg") {
      f.check = [](const FieldValue& v, const Entity* e) {
        return e && e->light && std::get<double>(v) < double(e->light->innerConeDeg)
                   ? "must not be less than the inner cone (" +
                         formatFieldValue(FieldType::Double, double(e->light->innerConeDeg), {}, 6) + " °)"
                   : std::string();
      };
      f.repair = [](Entity& e) { e.light->innerConeDeg = e.light->outerConeDeg; };
    } else if (f.key == "shadow_resolution") {
      f.animatable = false;
    }
  }

  out.push_back(optionalComponent<Camera>(
      "camera", "Camera", &Entity::camera,
      {doubleField<Entity>("fov_deg", "Vertical field of view", 1.0, 170.0, 1.0, "°",
                           [](Entity& e) -> double& { return e.camera->verticalFovDeg; }),
       focalLengthField(),
       doubleField<Entity>("near_m", "Near clip", 1e-4, 1e5, 0.01, "m",
                           [](Entity& e) -> double& { return e.camera->nearClip; }),
       doubleField<Entity>("far_m", "Far clip", 1e-2, 1e8, 100.0, "m",
                           [](Entity& e) -> double& { return e.camera->farClip; }),
       doubleField<Entity>("focus_distance_m", "Focus distance", 1e-3, 1e7, 0.1, "m",
                           [](Entity& e) -> double& { return e.camera->focusDistance; }),
       doubleField<Entity>("f_stop", "Aperture (f-stop)", 0.5, 128.0, 0.1, "",
                           [](Entity& e) -> double& { return e.camera->fStop; }),
       enumField<Entity>("stereo", "Stereo", {"Mono", "Off-axis", "Parallel", "Toe-in"},
                         [](Entity& e) -> Camera::Stereo& { return e.camera->stereo; }),
       doubleField<Entity>("interaxial_m", "Interaxial", 0.0, 1000.0, 0.001, "m",
                           [](Entity& e) -> double& { return e.camera->interaxial; }),
       doubleField<Entity>("convergence_m", "Convergence distance", 1e-3, 1e7, 0.1, "m",
                           [](Entity& e) -> double& { return e.camera->convergence; }),
       enumField<Entity>("pivot", "Rig pivot", {"Left", "Centre", "Right"},
                         [](Entity& e) -> Camera::Pivot& { return e.camera->pivot; })}));
  // The clip planes bound each other: near below far.
  for (EntityField& f : out.back().fields) {
    if (f.key == "near_m") {
      f.check = [](const FieldValue& v, const Entity* e) {
        return e && e->camera && std::get<double>(v) >= e->camera->farClip
                   ? "must be less than the far clip (" + formatFieldValue(FieldType::Double, e->camera->farClip, {}, 6) + " m)"
                   : std::string();
      };
      f.repair = [](Entity& e) { e.camera->nearClip = e.camera->farClip * 1e-3; };
    } else if (f.key == "far_m") {
      f.check = [](const FieldValue& v, const Entity* e) {
        return e && e->camera && std::get<double>(v) <= e->camera->nearClip
                   ? "must be greater than the near clip (" + formatFieldValue(FieldType::Double, e->camera->nearClip, {}, 6) +
                         " m)"
                   : std::string();
      };
      f.repair = [](Entity& e) { e.camera->farClip = e.camera->nearClip * 1e3; };
    }
  }

  // Which terrain it shows is a reference, written by scene_json next to
  // these fields ("terrain_id"), not an editable value: the Terrain panel
  // and the terrain commands manage it.
  out.push_back(optionalComponent<TerrainInstance>(
      "terrain", "Terrain", &Entity::terrain,
      {doubleField<Entity>("lod_error_px", "LOD error bound", 0.1, 64.0, 0.1, "px",
                           [](Entity& e) -> double& { return e.terrain->lodErrorPixels; })}));
  // An emitter's parameters are declared once in particles/emitter.h
  // (emitterParamDecls: numbers, MIN,MAX pairs, choices, lists and curves
  // this table has no types for); scene_json writes the component as
  // emitterToJson, `set EMITTER particles.FIELD` and the Particles panel go
  // through scene/particle_ops.h.
  out.push_back(optionalComponent<ParticleEmitter>("particles", "Particles", &Entity::particles, {}));
  return out;
}

// A count that chooses how much work a pass does (not a look to animate).
SettingsField notAnimated(SettingsField f) {
  f.animatable = false;
  return f;
}

std::vector<SettingsField> buildSettingsFields() {
  using S = SceneSettings;
  return {
      colorField<S>("sky_zenith", "Sky zenith", [](S& s) -> glm::vec3& { return s.skyZenith; }),
      colorField<S>("sky_horizon", "Sky horizon", [](S& s) -> glm::vec3& { return s.skyHorizon; }),
      colorField<S>("ground_color", "Ground", [](S& s) -> glm::vec3& { return s.groundColor; }),
      doubleField<S>("ambient", "Sky ambient", 0.0, 100.0, 0.05, "",
                     [](S& s) -> float& { return s.ambientIntensity; }),
      // Camera exposure in EV100 (light_units.h): lower is brighter.
      doubleField<S>("exposure_ev100", "Exposure (EV100)", -10.0, 30.0, 0.1, "EV",
                     [](S& s) -> float& { return s.exposureEv100; }),
      boolField<S>("show_grid", "Ground grid", [](S& s) -> bool& { return s.showGrid; }),
      enumField<S>("antialiasing", "Anti-aliasing", {"None", "FXAA", "MSAA 4x", "SMAA"},
                   [](S& s) -> Antialiasing& { return s.antialiasing; }),
      enumField<S>("tonemap", "Tone mapping", {"ACES", "None", "AgX", "PBR Neutral"},
                   [](S& s) -> Tonemap& { return s.tonemap; }),
      // An OpenColorIO view transform in the tone map's place; the config
      // itself (post.ocio_config) comes from `ocio import` / Import OCIO
      // config... (scene/ocio_config.h). An empty display or view is the
      // config's default.
      boolField<S>("post.view_transform.enabled", "View transform (OCIO)",
                   [](S& s) -> bool& { return s.post.viewTransform; }),
      [] {
        SettingsField f = stringField<S>("post.view_transform.display", "Display",
                                         [](S& s) -> std::string& { return s.post.display; });
        f.check = [](const FieldValue& v, const S* current) {
          return current ? displayViewProblem(current->post.ocioConfig, std::get<std::string>(v), "") : "";
        };
        f.repair = [](S& s) { s.post.display.clear(); };
        // A view the new display lacks gives way to its default (as
        // Blender's view box does when the display changes).
        f.set = [](S& s, const FieldValue& v) {
          // A name the stored config lacks is not taken (the check says why).
          if (!displayViewProblem(s.post.ocioConfig, std::get<std::string>(v), "").empty()) return;
          s.post.display = std::get<std::string>(v);
          if (!s.post.view.empty() && displayViewProblem(s.post.ocioConfig, s.post.display, "").empty() &&
              !displayViewProblem(s.post.ocioConfig, s.post.display, s.post.view).empty())
            s.post.view.clear();
        };
        return f;
      }(),
      [] {
        SettingsField f = stringField<S>("post.view_transform.view", "View",
                                         [](S& s) -> std::string& { return s.post.view; });
        f.check = [](const FieldValue& v, const S* current) {
          return current ? displayViewProblem(current->post.ocioConfig, current->post.display, std::get<std::string>(v))
                         : "";
        };
        f.repair = [](S& s) { s.post.view.clear(); };
        f.set = [](S& s, const FieldValue& v) {
          if (displayViewProblem(s.post.ocioConfig, s.post.display, std::get<std::string>(v)).empty())
            s.post.view = std::get<std::string>(v);
        };
        return f;
      }(),
      // The post chain (PostSettings, docs/rendering.md "Post-processing"):
      // settings.post.EFFECT.FIELD, each effect off until enabled.
      // Automatic exposure (core/exposure_meter.h): the metered EV100 is
      // clamped to [min, max]; the percentiles leave the darkest and the
      // brightest pixels out of the mean; speeds are per second.
      boolField<S>("post.auto_exposure.enabled", "Automatic exposure",
                   [](S& s) -> bool& { return s.post.autoExposure; }),
      doubleField<S>("post.auto_exposure.min_ev100", "Auto exposure minimum", -10.0, 30.0, 0.1, "EV",
                     [](S& s) -> float& { return s.post.autoExposureMinEv100; }),
      doubleField<S>("post.auto_exposure.max_ev100", "Auto exposure maximum", -10.0, 30.0, 0.1, "EV",
                     [](S& s) -> float& { return s.post.autoExposureMaxEv100; }),
      doubleField<S>("post.auto_exposure.compensation", "Exposure compensation", -10.0, 10.0, 0.1, "EV",
                     [](S& s) -> float& { return s.post.autoExposureCompensation; }),
      doubleField<S>("post.auto_exposure.low_percent", "Metering low percentile", 0.0, 100.0, 1.0, "%",
                     [](S& s) -> float& { return s.post.autoExposureLowPercent; }),
      doubleField<S>("post.auto_exposure.high_percent", "Metering high percentile", 0.0, 100.0, 1.0, "%",
                     [](S& s) -> float& { return s.post.autoExposureHighPercent; }),
      doubleField<S>("post.auto_exposure.speed_up", "Adaptation to brighter", 0.01, 1000.0, 0.1, "/s",
                     [](S& s) -> float& { return s.post.autoExposureSpeedUp; }),
      doubleField<S>("post.auto_exposure.speed_down", "Adaptation to darker", 0.01, 1000.0, 0.1, "/s",
                     [](S& s) -> float& { return s.post.autoExposureSpeedDown; }),
      // Probe renders per second of film: how finely the adaptation samples
      // the scene (its error against run time: bench_post).
      notAnimated(doubleField<S>("post.auto_exposure.probes_per_second", "Exposure probes per second", 0.5, 60.0,
                                 0.5, "/s", [](S& s) -> float& { return s.post.autoExposureProbesPerSecond; })),
      boolField<S>("post.bloom.enabled", "Bloom", [](S& s) -> bool& { return s.post.bloom; }),
      doubleField<S>("post.bloom.intensity", "Bloom intensity", 0.0, 10.0, 0.01, "",
                     [](S& s) -> float& { return s.post.bloomIntensity; }),
      doubleField<S>("post.bloom.threshold", "Bloom threshold", 0.0, 1e4, 0.05, "",
                     [](S& s) -> float& { return s.post.bloomThreshold; }),
      doubleField<S>("post.bloom.radius", "Bloom radius", 0.0, 1.0, 0.05, "",
                     [](S& s) -> float& { return s.post.bloomRadius; }),
      boolField<S>("post.chromatic_aberration.enabled", "Chromatic aberration",
                   [](S& s) -> bool& { return s.post.chromaticAberration; }),
      doubleField<S>("post.chromatic_aberration.px", "Chromatic aberration (corner)", 0.0, 50.0, 0.1, "px",
                     [](S& s) -> float& { return s.post.chromaticAberrationPx; }),
      boolField<S>("post.grade.enabled", "Colour grade", [](S& s) -> bool& { return s.post.grade; }),
      doubleField<S>("post.grade.temperature", "White balance temperature", -1.0, 1.0, 0.01, "",
                     [](S& s) -> float& { return s.post.temperature; }),
      doubleField<S>("post.grade.tint", "White balance tint", -1.0, 1.0, 0.01, "",
                     [](S& s) -> float& { return s.post.tint; }),
      boundedVec3Field<S>("post.grade.lift", "Lift", -1.0, 1.0, [](S& s) -> glm::vec3& { return s.post.lift; }),
      boundedVec3Field<S>("post.grade.gamma", "Gamma", 0.1, 10.0, [](S& s) -> glm::vec3& { return s.post.gamma; }),
      boundedVec3Field<S>("post.grade.gain", "Gain", 0.0, 10.0, [](S& s) -> glm::vec3& { return s.post.gain; }),
      doubleField<S>("post.grade.saturation", "Saturation", 0.0, 4.0, 0.01, "",
                     [](S& s) -> float& { return s.post.saturation; }),
      // The LUT itself (post.lut) comes from `lut import` / Import LUT...
      // (scene/color_lut.h); these turn it on and mix it in.
      boolField<S>("post.lut.enabled", "LUT", [](S& s) -> bool& { return s.post.lutEnabled; }),
      doubleField<S>("post.lut.intensity", "LUT intensity", 0.0, 1.0, 0.01, "",
                     [](S& s) -> float& { return s.post.lutIntensity; }),
      boolField<S>("post.vignette.enabled", "Vignette", [](S& s) -> bool& { return s.post.vignette; }),
      doubleField<S>("post.vignette.intensity", "Vignette intensity", 0.0, 1.0, 0.01, "",
                     [](S& s) -> float& { return s.post.vignetteIntensity; }),
      boolField<S>("post.grain.enabled", "Film grain", [](S& s) -> bool& { return s.post.grain; }),
      doubleField<S>("post.grain.intensity", "Grain intensity", 0.0, 1.0, 0.005, "",
                     [](S& s) -> float& { return s.post.grainIntensity; }),
      doubleField<S>("post.grain.size_px", "Grain size", 0.5, 8.0, 0.1, "px",
                     [](S& s) -> float& { return s.post.grainSizePx; }),
      // The stylised effects (docs/rendering.md "Stylised effects"), in the
      // chain's order after the grain.
      boolField<S>("post.kuwahara.enabled", "Kuwahara (painterly)", [](S& s) -> bool& { return s.post.kuwahara; }),
      doubleField<S>("post.kuwahara.radius_px", "Kuwahara radius", 0.5, 32.0, 0.5, "px",
                     [](S& s) -> float& { return s.post.kuwaharaRadiusPx; }),
      // q at most 16 keeps every sector weight above a float's smallest (shaders/kuwahara.frag).
      doubleField<S>("post.kuwahara.sharpness", "Kuwahara sharpness", 1.0, 16.0, 0.5, "",
                     [](S& s) -> float& { return s.post.kuwaharaSharpness; }),
      boolField<S>("post.comic.enabled", "Comic", [](S& s) -> bool& { return s.post.comic; }),
      doubleField<S>("post.comic.levels", "Comic levels", 2.0, 16.0, 1.0, "",
                     [](S& s) -> float& { return s.post.comicLevels; }),
      doubleField<S>("post.comic.dot_px", "Halftone cell", 2.0, 64.0, 0.5, "px",
                     [](S& s) -> float& { return s.post.comicDotPx; }),
      boolField<S>("post.outlines.enabled", "Outlines", [](S& s) -> bool& { return s.post.outlines; }),
      doubleField<S>("post.outlines.threshold", "Outline threshold", 0.01, 2.0, 0.01, "",
                     [](S& s) -> float& { return s.post.outlineThreshold; }),
      colorField<S>("post.outlines.color", "Outline colour", [](S& s) -> glm::vec3& { return s.post.outlineColor; }),
      boolField<S>("post.crt.enabled", "CRT", [](S& s) -> bool& { return s.post.crt; }),
      doubleField<S>("post.crt.curvature", "CRT curvature", 0.0, 0.5, 0.01, "",
                     [](S& s) -> float& { return s.post.crtCurvature; }),
      doubleField<S>("post.crt.scanlines", "Scanline darkening", 0.0, 1.0, 0.05, "",
                     [](S& s) -> float& { return s.post.crtScanlines; }),
      doubleField<S>("post.crt.lines", "Scanlines", 20.0, 2160.0, 10.0, "",
                     [](S& s) -> float& { return s.post.crtLinesPer1080; }),
      doubleField<S>("post.crt.mask", "Aperture mask", 0.0, 1.0, 0.05, "",
                     [](S& s) -> float& { return s.post.crtMask; }),
      enumField<S>("post.dither.mode", "Dithering", {"Off", "Bayer", "Blue noise", "Error diffusion"},
                   [](S& s) -> DitherMode& { return s.post.dither; }),
      doubleField<S>("post.dither.levels", "Dither levels", 2.0, 256.0, 1.0, "",
                     [](S& s) -> float& { return s.post.ditherLevels; }),
      // Stippling runs after the per-pixel effects above (so outlines come
      // out as dense dots) and before error diffusion.
      boolField<S>("post.stipple.enabled", "Stippling", [](S& s) -> bool& { return s.post.stipple; }),
      doubleField<S>("post.stipple.spacing_px", "Stipple spacing", 2.0, 32.0, 0.5, "px",
                     [](S& s) -> float& { return s.post.stippleSpacingPx; }),
      doubleField<S>("post.stipple.dot_px", "Stipple dot radius", 0.25, 8.0, 0.05, "px",
                     [](S& s) -> float& { return s.post.stippleDotPx; }),
      doubleField<S>("post.stipple.iterations", "Stipple relaxation steps", 0.0, 50.0, 1.0, "",
                     [](S& s) -> int& { return s.post.stippleIterations; }),
      // Screen-space error of mesh LODs (mesh/lod_chain.h selectLod); 0 draws full resolution.
      doubleField<S>("mesh_lod_error_px", "Mesh LOD error bound", 0.0, 64.0, 0.1, "px",
                     [](S& s) -> double& { return s.meshLodErrorPixels; }),
      // Cluster hierarchies' page budgets (scene/cluster_asset.h): under a
      // few MiB nothing but the roots would stay resident.
      doubleField<S>("clusters.gpu_budget_mb", "Cluster GPU budget", 16.0, 262144.0, 64.0, "MiB",
                     [](S& s) -> double& { return s.clusterGpuBudgetMb; }),
      doubleField<S>("clusters.cpu_budget_mb", "Cluster page cache", 16.0, 262144.0, 64.0, "MiB",
                     [](S& s) -> double& { return s.clusterCpuBudgetMb; }),
      // Shadows (docs/rendering.md "Shadows"). A map under 256 texels shows
      // nothing useful; over 8192 a 4-cascade array passes 1 GB.
      boolField<S>("shadows", "Shadows", [](S& s) -> bool& { return s.shadows; }),
      enumField<S>("shadow_quality", "Shadow quality", {"low", "medium", "high", "custom"},
                   [](S& s) -> ShadowQuality& { return s.shadowQuality; }),
      doubleField<S>("shadow_resolution", "Shadow map size (custom)", 256.0, 8192.0, 256.0, "px",
                     [](S& s) -> int& { return s.shadowResolution; }),
      doubleField<S>("shadow_cascades", "Sun cascades (custom)", 1.0, 4.0, 1.0, "",
                     [](S& s) -> int& { return s.shadowCascades; }),
      doubleField<S>("shadow_pcf", "Shadow filter radius (custom)", 0.0, 3.0, 1.0, "texels",
                     [](S& s) -> int& { return s.shadowPcfRadius; }),
      doubleField<S>("shadow_distance", "Sun shadow distance", 1.0, 100000.0, 10.0, "m",
                     [](S& s) -> double& { return s.shadowDistance; }),
      // Fog (scene_state.h FogMode, shaders/fog.glsl).
      enumField<S>("fog_mode", "Fog", {"none", "depth_cue", "exponential_height"},
                   [](S& s) -> FogMode& { return s.fogMode; }),
      colorField<S>("fog_colour", "Fog colour", [](S& s) -> glm::vec3& { return s.fogColour; }),
      doubleField<S>("fog_k1", "Depth cue k1", 1e-3, 1e3, 0.05, "", [](S& s) -> float& { return s.fogK1; }),
      doubleField<S>("fog_k2", "Depth cue k2", 0.0, 10.0, 1e-4, "/m", [](S& s) -> float& { return s.fogK2; }),
      doubleField<S>("fog_density", "Fog density", 0.0, 10.0, 1e-4, "/m", [](S& s) -> float& { return s.fogDensity; }),
      doubleField<S>("fog_height_falloff", "Fog height falloff", 0.0, 10.0, 1e-3, "/m",
                     [](S& s) -> float& { return s.fogHeightFalloff; }),
      doubleField<S>("fog_height", "Fog height", -1e5, 1e5, 1.0, "m", [](S& s) -> float& { return s.fogHeight; }),
      // Sky and environment (docs/rendering.md). Preetham's fit holds for
      // turbidity 2..10; below 1.7 its zenith colour leaves the gamut.
      enumField<S>("sky", "Sky", {"gradient", "analytic"}, [](S& s) -> SkyModel& { return s.sky; }),
      doubleField<S>("sky_turbidity", "Sky turbidity", 1.7, 10.0, 0.1, "",
                     [](S& s) -> float& { return s.skyTurbidity; }),
      doubleField<S>("sky_ground_albedo", "Ground albedo (sky)", 0.0, 1.0, 0.01, "",
                     [](S& s) -> float& { return s.skyGroundAlbedo; }),
      enumField<S>("ao", "Ambient occlusion", {"off", "ssao", "gtao"}, [](S& s) -> AmbientOcclusion& { return s.ao; }),
      doubleField<S>("ao_radius", "AO radius", 0.05, 20.0, 0.05, "m", [](S& s) -> float& { return s.aoRadius; }),
      doubleField<S>("ao_strength", "AO strength", 0.0, 4.0, 0.05, "", [](S& s) -> float& { return s.aoStrength; }),
      enumField<S>("ao_resolution", "AO resolution", {"half", "full"},
                   [](S& s) -> AoResolution& { return s.aoResolution; }),
      // Depth of field (docs/rendering.md "Depth of field"); the lens is the
      // camera's (focal_length_mm, f_stop, focus_distance_m).
      enumField<S>("depth_of_field", "Depth of field", {"off", "gather", "layered", "reference"},
                   [](S& s) -> DepthOfField& { return s.depthOfField; }),
      notAnimated(doubleField<S>("dof_layers", "DoF layers (layered)", 2.0, 16.0, 1.0, "",
                                 [](S& s) -> int& { return s.dofLayers; })),
      notAnimated(doubleField<S>("dof_reference_samples", "DoF lens samples (reference)", 64.0, 1024.0, 1.0, "",
                                 [](S& s) -> int& { return s.dofReferenceSamples; })),
      // Transparency (scene_state.h Transparency, docs/rendering.md).
      enumField<S>("transparency", "Transparency", {"abuffer", "abuffer_fixed", "kbuffer", "weighted", "reference"},
                   [](S& s) -> Transparency& { return s.transparency; }),
      doubleField<S>("kbuffer_k", "K-buffer depth (K)", 1.0, 32.0, 1.0, "", [](S& s) -> int& { return s.kbufferK; }),
      doubleField<S>("oit_memory_mb", "OIT memory cap", 1.0, 16384.0, 16.0, "MiB",
                     [](S& s) -> double& { return s.oitMemoryMb; }),
      // Where particles are evaluated (docs/particles.md, "Drawing").
      notAnimated(boolField<S>("particles_gpu", "Particles on the GPU", [](S& s) -> bool& { return s.particlesOnGpu; })),
  };
}

// Materials (scene/material.h), a list of their own. A texture is a
// reference (an id of SceneState::textures, 0 for none), not animatable.
template <class Access>
MaterialField textureField(std::string key, std::string label, Access access) {
  MaterialField f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.type = FieldType::AssetRef;
  f.animatable = false;
  f.get = [access](const Material& m) { return FieldValue(int64_t(access(const_cast<Material&>(m)))); };
  f.set = [access](Material& m, const FieldValue& v) { access(m) = TextureId(std::max<int64_t>(0, std::get<int64_t>(v))); };
  return f;
}

std::vector<MaterialField> buildMaterialFields() {
  using M = Material;
  MaterialField name;
  name.key = "name";
  name.label = "Name";
  name.type = FieldType::String;
  name.animatable = false;
  name.serialized = false;  // written by scene_json beside the id
  name.get = [](const M& m) { return FieldValue(m.name); };
  name.set = [](M& m, const FieldValue& v) { m.name = std::get<std::string>(v); };
  return {
      name,
      colorField<M>("base_color", "Base colour", [](M& m) -> glm::vec3& { return m.baseColor; }),
      textureField("base_color_texture", "Base colour texture", [](M& m) -> TextureId& { return m.baseColorTexture; }),
      doubleField<M>("opacity", "Opacity", 0.0, 1.0, 0.01, "", [](M& m) -> float& { return m.opacity; }),
      textureField("normal_map", "Normal map", [](M& m) -> TextureId& { return m.normalMap; }),
      doubleField<M>("normal_strength", "Normal strength", 0.0, 4.0, 0.05, "",
                     [](M& m) -> float& { return m.normalStrength; }),
      textureField("height_map", "Height map (parallax)", [](M& m) -> TextureId& { return m.heightMap; }),
      // Parallax relief beyond 0.5 m looks like a hole, not a surface: geometry's job.
      doubleField<M>("height_scale", "Height scale", 0.0, 0.5, 0.001, "m",
                     [](M& m) -> float& { return m.heightScale; }),
      doubleField<M>("roughness", "Roughness", 0.0, 1.0, 0.01, "", [](M& m) -> float& { return m.roughness; }),
      doubleField<M>("metallic", "Metallic", 0.0, 1.0, 0.01, "", [](M& m) -> float& { return m.metallic; }),
      doubleField<M>("specular", "Specular", 0.0, 1.0, 0.01, "", [](M& m) -> float& { return m.specular; }),
      doubleField<M>("shininess", "Shininess (Phong)", 1.0, 10000.0, 1.0, "",
                     [](M& m) -> float& { return m.shininess; }),
      colorField<M>("emission", "Emission", [](M& m) -> glm::vec3& { return m.emission; }),
      doubleField<M>("emission_strength", "Emission strength", 0.0, 1e5, 0.1, "",
                     [](M& m) -> float& { return m.emissionStrength; }),
      boolField<M>("alpha_cutout", "Alpha cut-out", [](M& m) -> bool& { return m.alphaCutout; }),
      doubleField<M>("alpha_threshold", "Cut-out threshold", 0.0, 1.0, 0.01, "",
                     [](M& m) -> float& { return m.alphaThreshold; }),
      boolField<M>("two_sided", "Two-sided", [](M& m) -> bool& { return m.twoSided; }),
      doubleField<M>("transmission", "Transmission", 0.0, 1.0, 0.01, "",
                     [](M& m) -> float& { return m.transmission; }),
      boolField<M>("unlit", "Unlit", [](M& m) -> bool& { return m.unlit; }),
      enumField<M>("model", "Lighting model", {"pbr", "lambert", "phong", "blinn_phong"},
                   [](M& m) -> LightingModel& { return m.model; }),
      enumField<M>("shading", "Shading", {"phong", "gouraud", "flat"}, [](M& m) -> ShadingMode& { return m.shading; }),
  };
}

}  // namespace

const std::vector<ComponentInfo>& entityComponents() {
  static const std::vector<ComponentInfo> table = buildEntityComponents();
  return table;
}

const std::vector<SettingsField>& settingsFields() {
  static const std::vector<SettingsField> table = buildSettingsFields();
  return table;
}

const std::vector<MaterialField>& materialFields() {
  static const std::vector<MaterialField> table = buildMaterialFields();
  return table;
}

const MaterialField* findMaterialField(std::string_view key) {
  for (const auto& f : materialFields())
    if (f.key == key) return &f;
  return nullptr;
}

const ComponentInfo* findComponent(std::string_view key) {
  for (const auto& c : entityComponents())
    if (c.key == key) return &c;
  return nullptr;
}

const EntityField* findEntityField(std::string_view path) {
  // A camera's post overrides are fields of their own (camera_post.h).
  if (path.substr(0, 12) == "camera.post.") return findCameraPostField(path.substr(12));
  const size_t dot = path.find('.');
  if (dot == std::string_view::npos) return nullptr;
  const ComponentInfo* c = findComponent(path.substr(0, dot));
  if (!c) return nullptr;
  const std::string_view key = path.substr(dot + 1);
  for (const auto& f : c->fields)
    if (f.key == key) return &f;
  return nullptr;
}

const SettingsField* findSettingsField(std::string_view key) {
  for (const auto& f : settingsFields())
    if (f.key == key) return &f;
  return nullptr;
}

namespace {
bool parseDouble(std::string_view s, double& v) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}
}  // namespace

template <class Target>
std::string fieldValueProblem(const FieldInfo<Target>& field, const FieldValue& v, const Target* current) {
  const auto range = [&] {
    return "must be from " + formatFieldValue(FieldType::Double, field.min, {}, 6) + " to " +
           formatFieldValue(FieldType::Double, field.max, {}, 6) + (field.unit.empty() ? "" : " " + field.unit);
  };
  switch (field.type) {
    case FieldType::Double: {
      const double d = std::get<double>(v);
      if (!std::isfinite(d)) return "must be a finite number";
      if (d < field.min || d > field.max) return range();
      break;
    }
    case FieldType::Vec3:
    case FieldType::Color: {
      const glm::dvec3 x = std::get<glm::dvec3>(v);
      for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(x[i])) return "must be three finite numbers";
        const bool bounded = field.type == FieldType::Color || field.min > -1e300 || field.max < 1e300;
        if (bounded && (x[i] < field.min || x[i] > field.max)) return "each channel " + range();
      }
      break;
    }
    case FieldType::Enum: {
      const int64_t i = std::get<int64_t>(v);
      if (i < 0 || size_t(i) >= field.enumNames.size()) return "must be one of the listed values";
      break;
    }
    default: break;
  }
  return field.check ? field.check(v, current) : std::string();
}

template std::string fieldValueProblem(const EntityField&, const FieldValue&, const Entity*);
template std::string fieldValueProblem(const SettingsField&, const FieldValue&, const SceneSettings*);
template std::string fieldValueProblem(const MaterialField&, const FieldValue&, const Material*);

namespace {
template <class Target>
std::optional<FieldValue> parseFieldText(const FieldInfo<Target>& field, std::string_view text, std::string& error) {
  switch (field.type) {
    case FieldType::Double: {
      double v;
      if (!parseDouble(text, v)) {
        error = "'" + std::string(text) + "' is not a finite number";
        return std::nullopt;
      }
      return FieldValue(v);
    }
    case FieldType::Bool:
      if (text == "true" || text == "1" || text == "on" || text == "yes") return FieldValue(true);
      if (text == "false" || text == "0" || text == "off" || text == "no") return FieldValue(false);
      error = "'" + std::string(text) + "' is not true/false";
      return std::nullopt;
    case FieldType::Enum: {
      for (size_t i = 0; i < field.enumNames.size(); ++i) {
        std::string a = field.enumNames[i], b(text);
        std::transform(a.begin(), a.end(), a.begin(), ::tolower);
        std::transform(b.begin(), b.end(), b.begin(), ::tolower);
        if (a == b) return FieldValue(int64_t(i));
      }
      double v;
      if (parseDouble(text, v) && v >= 0 && v < double(field.enumNames.size()) && v == std::floor(v))
        return FieldValue(int64_t(v));
      error = "'" + std::string(text) + "' is not one of:";
      for (const auto& n : field.enumNames) error += " " + n;
      return std::nullopt;
    }
    case FieldType::Vec3:
    case FieldType::Color: {
      glm::dvec3 v;
      size_t start = 0;
      for (int i = 0; i < 3; ++i) {
        const size_t comma = text.find(',', start);
        if ((i < 2 && comma == std::string_view::npos) || (i == 2 && comma != std::string_view::npos) ||
            !parseDouble(text.substr(start, i < 2 ? comma - start : std::string_view::npos), v[i])) {
          error = "'" + std::string(text) + "' is not three finite numbers x,y,z";
          return std::nullopt;
        }
        start = comma + 1;
      }
      return FieldValue(v);
    }
    case FieldType::String:
      return FieldValue(std::string(text));
    case FieldType::AssetRef: {
      // A whole number in digits: through a double, 1e308 or 2^63 became
      // an id no int64 holds (stored as 0: the mesh silently gone).
      int64_t v = -1;
      const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
      if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || v < 0) {
        error = "'" + std::string(text) + "' is not an asset id (a whole number; 0 for none)";
        return std::nullopt;
      }
      return FieldValue(v);
    }
  }
  return std::nullopt;
}

}  // namespace

// Text that parses but breaks the field's range or rule is refused here,
// with the rule: `set`, `key` and every other text entry say why.
template <class Target>
std::optional<FieldValue> parseFieldValue(const FieldInfo<Target>& field, std::string_view text,
                                          std::string& error) {
  std::optional<FieldValue> v = parseFieldText(field, text, error);
  if (!v) return std::nullopt;
  if (const std::string problem = fieldValueProblem(field, *v, static_cast<const Target*>(nullptr));
      !problem.empty()) {
    error = "'" + std::string(text) + "' is out of range: " + field.label + " " + problem;
    return std::nullopt;
  }
  return v;
}

template std::optional<FieldValue> parseFieldValue(const EntityField&, std::string_view, std::string&);
template std::optional<FieldValue> parseFieldValue(const SettingsField&, std::string_view, std::string&);
template std::optional<FieldValue> parseFieldValue(const MaterialField&, std::string_view, std::string&);

std::string formatFieldValue(FieldType type, const FieldValue& v,
                             const std::vector<std::string>& enumNames, int digits) {
  std::ostringstream s;
  s.precision(digits);
  switch (type) {
    case FieldType::Double: s << std::get<double>(v); break;
    case FieldType::Bool: s << (std::get<bool>(v) ? "true" : "false"); break;
    case FieldType::Enum: {
      const int64_t i = std::get<int64_t>(v);
      if (i >= 0 && size_t(i) < enumNames.size()) s << enumNames[size_t(i)];
      else s << i;
      break;
    }
    case FieldType::Vec3:
    case FieldType::Color: {
      const auto& x = std::get<glm::dvec3>(v);
      s << x.x << "," << x.y << "," << x.z;
      break;
    }
    case FieldType::String: s << std::get<std::string>(v); break;
    case FieldType::AssetRef: s << std::get<int64_t>(v); break;
  }
  return s.str();
}

}  // namespace hs::scene
