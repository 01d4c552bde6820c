// stb_image's implementation for the page (the desktop gets it from Debian's libstb, which
// libimgui links): png_writer.cpp decodes PNGs with stbi_load.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>
