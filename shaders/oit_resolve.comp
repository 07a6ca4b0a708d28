#version 450 core
// The compute variants of the transparency resolve (oit_resolve.glsl).
#define OIT_COMPUTE
#include "oit_resolve.glsl"
