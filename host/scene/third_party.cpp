// The one translation unit that compiles the header-only dependencies' implementations:
// stb_image (used by the OBJ texture path and by tinygltf), tinyobjloader and tinygltf.
// stb_image's implementation section has no include guard, so it is included once, here,
// and tinygltf is told not to include it again (TINYGLTF_NO_INCLUDE_STB_IMAGE).
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#include <tiny_gltf.h>
