#pragma once
// tinygltf's options, the same in every file that includes it: the class
// TinyGLTF's default image reader and writer members depend on them, so a
// file that includes <tiny_gltf.h> without them would point those members
// at stb functions mesh/tinygltf_impl.cpp does not compile. No image
// decoding or writing through stb (textures come through texture_decode.h),
// no external images read.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
