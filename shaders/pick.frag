#version 450 core
// Writes the index (1-based) of the drawn instance for viewport picking.
uniform uint uPickId;
layout(location = 0) out uint outId;
void main() { outId = uPickId; }
