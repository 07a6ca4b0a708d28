// What every pass of a frame shares, in uniform and storage buffers with
// fixed binding points (render/frame_blocks.h is the C++ side; the layouts
// must match it member for member).
//
// Spaces: "eye space" has the world's axes and its origin at the eye of the
// view being drawn. Object matrices and light positions are relative to the
// frame origin (the frame's mono camera), formed in double on the CPU; a
// view adds its small eye offset. So a scene at UTM coordinates reaches the
// GPU as small floats, and both eyes of a stereo pair share one set of
// object and light data.
//
// Binding points (render/frame_blocks.h, enum Binding): uniform blocks 0
// frame, 1 view, 5 shadows, 6 environment; storage buffers 2 lights,
// 3 objects, 4 materials, 7 the light grid (9 its light indices, 10 its
// statistics: light_clusters.glsl), 11 spot/point shadow data.
// Texture units: 0-7 a material's textures, 8-11 sun shadow maps, 12-15
// environment maps, 16-19 spot/point shadow maps.
#ifndef HS_FRAME_BLOCKS_GLSL
#define HS_FRAME_BLOCKS_GLSL

layout(std140, binding = 0) uniform FrameBlock {
  vec4 sunDir;        // xyz: towards the sun (world); w: 1 if the scene has a sun
  vec4 sunColor;      // rgb: linear colour x intensity
  vec4 skyZenith;     // rgb
  vec4 skyHorizon;    // rgb
  vec4 groundColor;   // rgb
  vec4 params;        // x: ambient intensity, y: exposure multiplier, z: light count, w: unused
  // Sky and environment (environment.glsl):
  vec4 environment;   // x: 1 when the environment maps (block 6, unit 12) hold the analytic sky
  // The frame's time, a pure function of the timeline (render/frame_blocks.h):
  vec4 time;          // x: seconds, y: frame number, z: fract(seconds) (from double), w: 1 / fps
} frame;

layout(std140, binding = 1) uniform ViewBlock {
  mat4 projection;    // reversed-Z, [0,1] depth
  mat4 viewRotation;  // eye space to view space (world to camera rotation)
  mat4 invViewRotation;
  vec4 eyeOffset;     // xyz: the eye minus the frame origin (metres)
  vec4 viewport;      // width, height, 1/width, 1/height
  vec4 tanHalfFov;    // x: tan(fovY/2) * aspect, y: tan(fovY/2), zw: projection shift (NDC)
} view;

struct Light {
  vec4 position;      // xyz: relative to the frame origin; w: range (m)
  vec4 color;         // rgb: colour x luminous intensity (candela, scene units); w: type (1 point, 2 spot)
  vec4 direction;     // xyz: the way a spot shines (unit)
  vec4 spot;          // x: 1 / (cos inner - cos outer), y: -cos outer * x (half angles); zw: shadows' own
};
layout(std430, binding = 2) readonly buffer LightBlock { Light lights[]; };

struct Object {
  mat4 model;         // object to eye space of the frame origin (translation relative to it)
  mat4 normalMatrix;  // mat3 in the upper left
  vec4 tint;          // rgb
};
layout(std430, binding = 3) readonly buffer ObjectBlock { Object objects[]; };

#endif
