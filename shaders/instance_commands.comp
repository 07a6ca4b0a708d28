#version 450 core
// The indirect draw commands of an instanced draw source
// (render/instanced_source.h), one per view and part (a type's submesh):
// its index range, and the instance count shaders/instance_cull.comp
// found for the part's type in that view.
layout(local_size_x = 64) in;

struct Command {  // DrawElementsIndirectCommand, 20 bytes
  uint count;
  uint instanceCount;
  uint firstIndex;
  uint baseVertex;
  uint baseInstance;
};
layout(std430, binding = 20) readonly buffer Parts { uvec4 parts[]; };  // x: index count, y: first index, z: type
layout(std430, binding = 21) writeonly buffer Commands { Command commands[]; };
layout(std430, binding = 22) readonly buffer VisibleCounts { uint counts[]; };

uniform uint uParts;
uniform uint uViews;
uniform uint uTypes;

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= uParts * uViews) return;
  uint v = k / uParts;
  uvec4 p = parts[k % uParts];
  commands[k] = Command(p.x, counts[v * uTypes + p.z], p.y, 0u, 0u);
}
