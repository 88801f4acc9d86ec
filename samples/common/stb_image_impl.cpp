// The one translation unit holding stb_image's implementation (compiled with warnings off: it is
// third-party code), PNG decoding only. Only image_io.cpp (read_png) calls it.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>
