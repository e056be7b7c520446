// tinygltf's implementation (see third_party_stb_image.cpp for why each has its own file).
// tinygltf would include stb_image's implementation again: it is told not to, and gets the
// declarations only.
#include <stb_image.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#include <tiny_gltf.h>
