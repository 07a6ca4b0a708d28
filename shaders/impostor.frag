#version 450 core
// Octahedral impostors (shaders/impostor.vert draws the card; render/
// impostor_cache.h bakes the atlas). Per pixel, for each of the three
// frames the card blends: where the ray from the drawn view's eye through
// the card's point meets the frame's picture plane gives the texel; its
// coverage-weighted colour, normal and depth (impostor_bake.frag) are
// blended by the frames' weights, and the depth puts the surface point
// back on the ray. So the impostor covers what the mesh covers (cut-out
// at half coverage), is lit with the normal its frames saw and the
// material of its mesh's largest part (uMaterial), and writes the depth
// of that point: it meets the ground, receives shadows and casts them
// where the mesh would, and each eye of a stereo pair sees its own depth.
// Variants: (none) lit, the opaque surface pass's defines; IMPOSTOR_PICK
// the id pass (pick.frag's output); IMPOSTOR_DEPTH shadow maps (depth
// only). The layered depth of field's A-buffer capture of every surface
// (render/abuffer.h) has three, each keyed by the depth computed here, not
// the card's: IMPOSTOR_ABUFFER_COUNT (abuffer_count.frag's work),
// IMPOSTOR_ABUFFER_KEYS (abuffer_keys.frag's) and HS_OIT with
// HS_OIT_ABUFFER (lit, stored opaque in its node: oit_store.glsl). Every
// variant drops the same pixels: under half coverage, and the fade's
// (instance_fade.glsl).
#if defined(IMPOSTOR_ABUFFER_COUNT) || defined(IMPOSTOR_ABUFFER_KEYS)
#define IMPOSTOR_CAPTURE
#endif
#include "frame_blocks.glsl"
#include "impostor.glsl"
#include "instance_fade.glsl"
// The A-buffer's declarations and its key, outside any #if: the shader
// library expands a file once, where it is first included (oit_output.glsl
// includes them too, inside its own #if). Unused, they cost nothing.
// Impostors never reach the K-buffer's slots: the key alone.
#include "abuffer.glsl"
#define OIT_KEY_ONLY
#include "oit_kbuffer.glsl"
#include "abuffer_key_store.glsl"
#if !defined(IMPOSTOR_PICK) && !defined(IMPOSTOR_DEPTH) && !defined(IMPOSTOR_CAPTURE)
#include "lighting.glsl"
#include "material_surface.glsl"
#ifdef HS_OIT
#include "oit_output.glsl"
#undef main  // oit_output.glsl renames mesh.frag's main; this shader has its own
#endif
layout(location = 0) out vec4 outColor;
#ifdef HS_OIT
#include "oit_store.glsl"
#endif
#endif
#ifdef IMPOSTOR_PICK
uniform uint uPickBase;
layout(location = 0) out uint outId;
#endif

in vec3 vCard;
flat in vec4 vViewer;
flat in vec2 vFrames[3];
flat in vec3 vWeights;
flat in mat3 vRotation;
flat in vec3 vScale;
flat in vec3 vOrigin;
flat in uint vObject;

uniform vec4 uImpostorSphere;  // level 0's bounds: centre (mesh space), radius
layout(binding = 3) uniform sampler2D uImpostorAlbedo;       // sRGB: rgb x coverage, a: coverage
layout(binding = 4) uniform sampler2D uImpostorNormalDepth;  // (normal x 0.5 + 0.5, depth) x coverage

void main() {
  vec3 c = uImpostorSphere.xyz;
  float r = uImpostorSphere.w;
  // Along the ray, away from the viewer.
  vec3 ray = vViewer.w > 0.5 ? normalize(vCard - vViewer.xyz) : -vViewer.xyz;
  float coverage = 0.0;
  vec3 colour = vec3(0.0), normal = vec3(0.0), point = vec3(0.0);
  const float inset = 0.5 / float(IMPOSTOR_FRAME_PIXELS);
  for (int k = 0; k < 3; ++k) {
    vec3 d = impostorFrameDirection(vFrames[k]);
    vec3 right, up;
    impostorBasis(d, right, up);
    float along = min(dot(ray, d), -0.05);  // the frames blended face the viewer: negative but for grazing rays
    vec3 h = vCard + (dot(c - vCard, d) / along) * ray - c;
    vec2 uv = vec2(dot(h, right), dot(h, up)) / r * 0.5 + 0.5;
    float inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) ? 1.0 : 0.0;
    vec2 atlas = (vFrames[k] + clamp(uv, vec2(inset), vec2(1.0 - inset))) / kImpostorFrames;
    vec4 a = texture(uImpostorAlbedo, atlas);
    vec4 nd = texture(uImpostorNormalDepth, atlas);
    float w = vWeights[k] * inside;
    coverage += w * a.a;
    colour += w * a.rgb;
    normal += w * (2.0 * nd.rgb - a.a);
    // The frame's surface point on this ray: its depth is (nd.a / a.a) in
    // [0, 1] across the sphere along d.
    float offset = a.a > 1e-3 ? (nd.a / a.a * 2.0 - 1.0) * r : 0.0;
    point += w * a.a * (vCard + ((offset - dot(vCard - c, d)) / along) * ray);
  }
  if (coverage < 0.5) discard;
  instanceFadeDiscard();
  vec3 pMesh = point / coverage;
#ifdef IMPOSTOR_DEPTH
  // Two texels further from the light: the frames the camera blends see
  // the surface a little apart from the light's, and gl_FragDepth takes no
  // polygon offset.
  pMesh += ray * (4.0 * r / float(IMPOSTOR_FRAME_PIXELS));
#endif
  vec3 p = vRotation * (pMesh * vScale) + vOrigin - view.eyeOffset.xyz;
  vec4 clip = view.projection * (view.viewRotation * vec4(p, 1.0));
  const float depth = clamp(clip.z / clip.w, 0.0, 1.0);
#if defined(IMPOSTOR_CAPTURE)
  // The capture stores nothing from a helper invocation (oit_main.glsl).
  if (gl_HelperInvocation) return;
#ifdef IMPOSTOR_ABUFFER_COUNT
  abufferCountFragment(ivec2(gl_FragCoord.xy));
#else
  abufferKeyFragment(ivec2(gl_FragCoord.xy), depth, oitKey(depth, vObject, uint(gl_PrimitiveID)));
#endif
#elif defined(IMPOSTOR_PICK)
  gl_FragDepth = depth;
  outId = uPickBase + vObject;
#elif defined(IMPOSTOR_DEPTH)
  gl_FragDepth = depth;
#else
  vec3 n = vRotation * (normal / vScale);
  n = dot(n, n) > 1e-12 ? normalize(n) : normalize(-p);
  if (dot(n, p) > 0.0) n = -n;  // the side the eye sees, as two-sided leaves are lit
  Material m = materials[uMaterial];
  outColor = vec4(shadeSurface(materialSurface(m, colour / coverage, p, n)), hsAmbientShare);
#ifdef HS_OIT
  // Cut out, so opaque where it covers.
  if (gl_HelperInvocation) return;
  oitStoreAt(vec4(outColor.rgb, 1.0), vObject, length(p), depth);
#else
  gl_FragDepth = depth;
#endif
#endif
}
