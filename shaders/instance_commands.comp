#version 450 core
// Pass 4 of an instanced draw source's GPU culling (render/
// instanced_source.h): the indirect draw commands, one per view and part (a
// submesh of a draw group's mesh: a type at one level): its index range,
// and the instance count shaders/instance_cull.comp found for the part's
// group in that view. mesh.vert finds the group's list from the group's
// first slot (binding 23), so every command starts at instance 0.
layout(local_size_x = 64) in;

struct Command {  // DrawElementsIndirectCommand, 20 bytes
  uint count;
  uint instanceCount;
  uint firstIndex;
  uint baseVertex;
  uint baseInstance;
};
layout(std430, binding = 20) readonly buffer Parts { uvec4 parts[]; };  // x: index count, y: first index, z: group
layout(std430, binding = 21) writeonly buffer Commands { Command commands[]; };
layout(std430, binding = 22) readonly buffer VisibleCounts { uint counts[]; };

uniform uint uParts;
uniform uint uViews;
uniform uint uGroups;

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= uParts * uViews) return;
  uint v = k / uParts;
  uvec4 p = parts[k % uParts];
  commands[k] = Command(p.x, counts[v * uGroups + p.z], p.y, 0u, 0u);
}
