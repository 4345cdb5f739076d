// Dear ImGui's OpenGL 3 backend, compiled here against OSMesa's GL entry points. Debian's
// prebuilt libimgui.a carries a copy built with a loader that resolves through libGL, which must
// not be linked beside OSMesa (platform-notes.md); this build of the backend (its source ships in
// libimgui-dev) uses direct GL prototypes instead.
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#include SPINFOLD_IMGUI_OPENGL3_SOURCE
