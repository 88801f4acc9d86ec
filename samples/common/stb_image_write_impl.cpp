// The one translation unit holding stb_image_write's implementation (compiled with warnings off:
// it is third-party code). Only image_io.cpp calls it.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
