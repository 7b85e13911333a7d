// The implementations of the header-only parsers the loaders use (Debian's tinygltf 2.7,
// tinyobjloader and stb_image), compiled here with penumbra's own flags rather than linked from
// the distribution's shared libraries: the fuzz and sanitizer builds then instrument the parsing
// code itself, and the installed package has no extra run-time dependency. Built without the
// project's warnings (third-party code).
#include "stb_allocation_limit.h"
#define STB_IMAGE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
#define STBI_MALLOC(size) penumbra::scene::stbLimitedMalloc(size)
#define STBI_REALLOC(pointer, size) penumbra::scene::stbLimitedRealloc(pointer, size)
#define STBI_FREE(pointer) std::free(pointer)
#include "stb_image.h"

#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
