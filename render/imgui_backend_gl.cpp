// Dear ImGui's OpenGL 3 backend, compiled here against the current context's GL table
// (render/gl_api.h). Debian's prebuilt libimgui.a carries a copy built with a loader that resolves
// through libGL, which must not be linked beside OSMesa (docs/platform-notes.md) and would miss a
// context made by the other backend; this build of the backend (its source ships in
// libimgui-dev) calls through the table instead.
#include "render/gl_api.h"

#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#include SPINFOLD_IMGUI_OPENGL3_SOURCE
