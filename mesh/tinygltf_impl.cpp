// tinygltf's implementation, compiled once here (the header-only build,
// not Debian's libtinygltf.so, so the options in tinygltf_options.h are
// ours; mesh/gltf_geometry.cpp passes a loader that keeps images
// undecoded), and Draco decoded by gltf_geometry.cpp itself with every
// index checked (tinygltf's own Draco path does not check).
#define TINYGLTF_IMPLEMENTATION
#include "mesh/tinygltf_options.h"
