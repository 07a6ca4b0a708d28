#version 450 core
// Particle billboards by vertex pulling (render/particle_source.h): six
// vertices per particle (gl_VertexID: the quad's corner), gl_InstanceID +
// uFirst the particle in the frame's particle buffer (particles::
// PackedParticle, std430, 64 bytes). Positions are relative to the frame
// origin, formed in double on the CPU (particles::packFrame), so an emitter
// at UTM coordinates arrives as small floats; a view adds its eye offset.
//   uFacing 0: facing the camera, turned by the particle's rotation
//   uFacing 1: stretched along its velocity as seen on screen (sparks, rain)
#include "frame_blocks.glsl"

struct PackedParticle {
  vec3 position;  // relative to the frame origin (m)
  float size;     // the sprite's width (m)
  vec4 colour;    // linear RGB, opacity
  vec3 velocity;  // m/s, world axes
  float rotationDeg;
  uint frame;     // flipbook frame
  uint variant;   // random bits of the particle
  uint pad0, pad1;
};
layout(std430, binding = 27) readonly buffer ParticleBlock { PackedParticle particles[]; };

uniform uint uFirst;        // the emitter's first particle in the buffer
uniform uint uObject;       // the transparency key's object (the emitter)
uniform int uFacing;
uniform float uStretchSeconds;  // velocity facing: the quad reaches this far along the motion
uniform int uLayerBase, uLayerCount;  // the sprite's layers (a flipbook's frames) in the array
uniform float uSpriteTexels;  // the sprites' width in texels (the level of detail)

out vec3 vEyePos;
out vec2 vSpriteUv;
flat out float vSpriteLayer;
flat out float vSpriteLod;
flat out vec4 vParticleColour;
flat out uint vObject;
// The key, count and lit passes draw the same quads with different
// fragment shaders and match fragments by depth (mesh.vert says why).
invariant gl_Position;

const vec2 kCorners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));

void main() {
  const PackedParticle p = particles[uFirst + uint(gl_InstanceID)];
  const vec2 corner = kCorners[gl_VertexID];
  vObject = uObject;
  vParticleColour = p.colour;
  vSpriteLayer = float(uLayerBase + int(p.frame % uint(max(uLayerCount, 1))));
  vSpriteUv = vec2(0.5 + 0.5 * corner.x, 0.5 - 0.5 * corner.y);  // the image's first row at the top

  const vec3 eye = p.position - view.eyeOffset.xyz;
  const vec3 centre = (view.viewRotation * vec4(eye, 0.0)).xyz;  // camera looks down -z
  const float half_ = 0.5 * p.size;
  vec2 offset;
  const vec2 motion = (view.viewRotation * vec4(p.velocity, 0.0)).xy * uStretchSeconds;
  if (uFacing == 1 && dot(motion, motion) > 1e-12) {
    // Along the motion: the quad's long axis follows it (half the motion
    // each way around the particle), its width is the size.
    const vec2 along = normalize(motion);
    const vec2 across = vec2(-along.y, along.x);
    offset = corner.y * along * (half_ + 0.5 * length(motion)) + corner.x * across * half_;
  } else {
    const float a = radians(p.rotationDeg);
    const mat2 turn = mat2(cos(a), sin(a), -sin(a), cos(a));
    offset = turn * corner * half_;
  }
  // A dead or invisible particle (opacity 0) draws nothing: outside the clip volume.
  const vec3 at = centre + vec3(offset, 0.0);
  vEyePos = (view.invViewRotation * vec4(at, 0.0)).xyz;
  gl_Position = p.colour.a > 0.0 && p.size > 0.0 ? view.projection * vec4(at, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);

  // Level of detail from the sprite's width on screen (texels per pixel),
  // the same for every fragment of the particle.
  const float pixels = p.size * view.viewport.y / (2.0 * view.tanHalfFov.y * max(-centre.z, 1e-4));
  vSpriteLod = max(log2(uSpriteTexels / max(pixels, 1e-3)), 0.0);
}
