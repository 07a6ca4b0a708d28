#version 450 core
// Meshes, camera-relative (frame_blocks.glsl): the object's matrix is
// relative to the frame origin, formed in double on the CPU, so vertices far
// from the world origin arrive here as small floats.
//
// Variant INSTANCED draws an instanced source's instances (render/
// instanced_source.h; shaders/instances.glsl): gl_InstanceID indexes the
// view's part of its draw group's list (uInstanceBase + the group's first
// slot), the instance's compact record gives the placement (a scale across
// and one along the height: normals take the inverse transpose,
// R (n / s), normalised in mesh.frag as the meshes' normal matrix is), the
// type's wind sways it (instances.glsl instanceWindOffset, a pure function
// of FrameBlock.time; response 0 skips it, so a stiff type is placed to
// the bit as with no wind), vInstanceFade carries the share of its pixels
// its fade drops (instance_fade.glsl), and vObject its stable id (picking,
// the transparency key); no per-object tint. The wind bends positions,
// not normals: a bend of a few degrees at most at the tip.
//
// Variant SHADING_GOURAUD lights here, once per vertex (the survey's
// Gouraud shading), with the material's untextured colour; mesh.frag then
// multiplies the interpolated light by the texture.
#include "frame_blocks.glsl"
#ifdef SHADING_GOURAUD
#include "lighting.glsl"
#include "material_surface.glsl"
out vec3 vLit;
#endif

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
#ifdef INSTANCED
#include "instances.glsl"
layout(std430, binding = 19) readonly buffer VisibleInstances { uint visibleInstances[]; };
layout(std430, binding = 23) readonly buffer InstanceGroupBase { uint instanceGroupBase[]; };
uniform uint uInstanceBase;  // this view's first slot
uniform uint uGroup;         // the draw group (type, level) of the part drawn
uniform vec3 uLodEye;        // the LOD view's eye, relative to the frame origin
uniform vec4 uInstanceType;  // x: cull distance (0: none), y: fade length, z: wind response, w: mesh height (0: no wind)
flat out float vInstanceFade;
#else
layout(location = 7) in uint aObject;  // per instance: index into objects[]
#endif
#ifdef HAS_TANGENTS
layout(location = 3) in vec4 aTangent;  // mesh/tangents.h; only meshes with normal or height maps have them
out vec4 vTangent;
#endif

out vec3 vEyePos;
out vec3 vNormal;
out vec2 vUv;
flat out uint vObject;
// The same position in every program built from this file: the
// transparency passes draw a mesh twice with different fragment shaders
// (a key pass, then the lit pass: render/abuffer.h, render/oit.h) and match
// fragments by their depth, which a differently optimised variant could
// round otherwise.
invariant gl_Position;

void main() {
#ifdef INSTANCED
  Instance inst = instances[visibleInstances[uInstanceBase + instanceGroupBase[uGroup] + uint(gl_InstanceID)]];
  mat3 rotation = instanceRotation(inst);
  vec3 scale = instanceScale(inst);
  vec3 origin = instanceOrigin(inst);
  vec3 p = rotation * (aPosition * scale) + origin;
  if (uInstanceType.z > 0.0 && uInstanceType.w > 0.0)
    p += instanceWindOffset(uInstanceType.z, aPosition.z, uInstanceType.w, scale.z, inst.rotationTypeId.w, frame.time);
  p -= view.eyeOffset.xyz;
  vNormal = rotation * (aNormal / scale);
  vObject = inst.rotationTypeId.w;
  vInstanceFade = instanceFade(length(origin - uLodEye), uInstanceType.x, uInstanceType.y);
  vec3 tint = vec3(1.0);
#ifdef HAS_TANGENTS
  vTangent = vec4(rotation * (aTangent.xyz * scale), aTangent.w);
#endif
#else
  Object o = objects[aObject];
  vec3 p = (o.model * vec4(aPosition, 1.0)).xyz - view.eyeOffset.xyz;
  vNormal = mat3(o.normalMatrix) * aNormal;
  vObject = aObject;
  vec3 tint = o.tint.rgb;
#ifdef HAS_TANGENTS
  vTangent = vec4(mat3(o.model) * aTangent.xyz, aTangent.w);
#endif
#endif
  vEyePos = p;
  vUv = aUv;
  gl_Position = view.projection * (view.viewRotation * vec4(p, 1.0));
#ifdef SHADING_GOURAUD
  Material m = materials[uMaterial];
  vec3 albedo = m.baseColor.rgb * tint;
  if (hasFlag(m, MAT_UNLIT)) {
    vLit = applyFog(albedo + m.emission.rgb, p);
  } else {
    vec3 n = normalize(vNormal);
    // The side the eye sees (no gl_FrontFacing per vertex).
    if (hasFlag(m, MAT_TWO_SIDED) && dot(n, p) > 0.0) n = -n;
    vLit = shadeSurface(materialSurface(m, albedo, p, n));
  }
#endif
}
