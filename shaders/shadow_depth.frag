#version 450 core
// Shadow maps hold depth only: nothing to write (render/passes/shadow_passes.cpp).
void main() {}
