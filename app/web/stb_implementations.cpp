// stb_rect_pack and stb_truetype for Dear ImGui's font atlas in the web build. Debian's
// libimgui is built against Debian's stb (libstb-dev) and links its library; the web build
// compiles ImGui the same way (app/web/CMakeLists.txt) and the implementations here, from
// the same headers, since libstb is not compiled to WebAssembly.
#define STB_RECT_PACK_IMPLEMENTATION
#include <stb/stb_rect_pack.h>
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb/stb_truetype.h>
