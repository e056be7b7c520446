// tinyobjloader's implementation (see third_party_stb_image.cpp for why each has its own file).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
