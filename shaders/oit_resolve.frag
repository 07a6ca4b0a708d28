#version 450 core
// The fragment variants of the transparency resolve (oit_resolve.glsl).
#include "oit_resolve.glsl"
