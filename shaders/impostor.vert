#version 450 core
// Octahedral impostors (render/instanced_source.h, the far level of a
// type; render/impostor_cache.h bakes the atlas): one card per instance,
// drawn from the same visible lists and indirect commands as the mesh
// levels (gl_InstanceID indexes the view's part of the impostor's draw
// group; gl_VertexID 0..3 is the corner). The card stands at the centre of
// level 0's bounding sphere, square to the direction the "facing" viewer
// sees the instance from, large enough to hold the sphere's outline; the
// same direction chooses the three frames shaders/impostor.frag blends.
// For the camera views the facing viewer is the LOD eye (FrameContext::
// lodView), so both eyes of a stereo pair draw the same card from the same
// frames (the fragment shader's ray from each eye gives the depth each eye
// sees); a shadow view faces its own light. Everything in the instance's
// mesh space (the atlas's): a point x goes to the world as R (S x) + O.
// No wind: at the distances the LOD rule draws impostors from, the sway
// is under its error (docs/rendering.md "Impostors").
#include "frame_blocks.glsl"
#include "instances.glsl"
#include "impostor.glsl"

layout(std430, binding = 19) readonly buffer VisibleInstances { uint visibleInstances[]; };
layout(std430, binding = 23) readonly buffer InstanceGroupBase { uint instanceGroupBase[]; };
uniform uint uInstanceBase;    // this view's first slot
uniform uint uGroup;           // the impostor's draw group
uniform vec3 uLodEye;          // the LOD view's eye, relative to the frame origin
uniform vec4 uInstanceType;    // x: cull distance (0: none), y: fade length
uniform vec4 uImpostorSphere;  // level 0's bounds: centre (mesh space), radius
uniform int uImpostorFacing;   // 0: the LOD eye faces the card; 1: the view drawn does (shadow views)

flat out float vInstanceFade;
flat out uint vObject;
out vec3 vCard;                // the card's point (mesh space)
flat out vec4 vViewer;         // the drawn view's eye (mesh space, w 1), or the way towards it (w 0: orthographic)
flat out vec2 vFrames[3];      // the frames blended (grid indices)
flat out vec3 vWeights;
flat out mat3 vRotation;
flat out vec3 vScale;
flat out vec3 vOrigin;         // relative to the frame origin

// The drawn view's viewer relative to the frame origin, from its clip
// matrix (camera views: projection x rotation about eyeOffset; shadow
// views: the light's clip matrix from the frame origin, no rotation or
// offset): the eye of a perspective view (w 1), the point its rows x, y
// and w all vanish at; or, for an orthographic one (the sun's cascades),
// the way towards the viewer (w 0): along both x and y rows' null
// direction, the side where reversed depth grows.
vec4 impostorViewer() {
  mat4 m = view.projection * view.viewRotation;
  vec4 rx = vec4(m[0][0], m[1][0], m[2][0], m[3][0]);
  vec4 ry = vec4(m[0][1], m[1][1], m[2][1], m[3][1]);
  vec4 rz = vec4(m[0][2], m[1][2], m[2][2], m[3][2]);
  vec4 rw = vec4(m[0][3], m[1][3], m[2][3], m[3][3]);
  if (dot(rw.xyz, rw.xyz) < 1e-20) {
    vec3 d = normalize(cross(rx.xyz, ry.xyz));
    return vec4(dot(rz.xyz, d) < 0.0 ? -d : d, 0.0);
  }
  mat3 a = transpose(mat3(rx.xyz, ry.xyz, rw.xyz));
  return vec4(inverse(a) * -vec3(rx.w, ry.w, rw.w) + view.eyeOffset.xyz, 1.0);
}

void main() {
  Instance inst = instances[visibleInstances[uInstanceBase + instanceGroupBase[uGroup] + uint(gl_InstanceID)]];
  mat3 rotation = instanceRotation(inst);
  vec3 scale = instanceScale(inst);
  vec3 origin = instanceOrigin(inst);
  mat3 toMesh = transpose(rotation);
  vec3 c = uImpostorSphere.xyz;
  float r = uImpostorSphere.w;
  vec4 seen = impostorViewer();
  vec4 viewer = seen.w > 0.5 ? vec4((toMesh * (seen.xyz - origin)) / scale, 1.0)
                             : vec4(normalize((toMesh * seen.xyz) / scale), 0.0);
  vec4 facing = uImpostorFacing == 0 ? vec4((toMesh * (uLodEye - origin)) / scale, 1.0) : viewer;
  vec3 towards = facing.w > 0.5 ? facing.xyz - c : facing.xyz;
  float distance = length(towards);
  vec3 dir = distance > 0.0 ? towards / distance : vec3(0.0, 0.0, 1.0);
  // From a point at distance D the sphere's outline reaches r D / sqrt(D^2
  // - r^2) across the card's plane (held to 4 r: the LOD rule never draws
  // an impostor from that close).
  float halfSize = r;
  if (facing.w > 0.5) halfSize = distance > r * 1.0308 ? r * distance / sqrt(distance * distance - r * r) : 4.0 * r;
  vec3 right, up;
  impostorBasis(dir, right, up);
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  vec3 q = c + halfSize * (corner.x * right + corner.y * up);
  vec3 p = rotation * (q * scale) + origin - view.eyeOffset.xyz;
  gl_Position = view.projection * (view.viewRotation * vec4(p, 1.0));
  vec2 frames[3];
  impostorBlend(dir, frames, vWeights);
  vFrames = frames;
  vCard = q;
  vViewer = viewer;
  vRotation = rotation;
  vScale = scale;
  vOrigin = origin;
  vObject = inst.rotationTypeId.w;
  vInstanceFade = instanceFade(length(origin - uLodEye), uInstanceType.x, uInstanceType.y);
}
