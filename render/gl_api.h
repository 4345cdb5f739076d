// The GL entry points the renderer and Dear ImGui's backend call, looked up through the backend
// that made the current context (OSMesaGetProcAddress, eglGetProcAddress) instead of linked by
// name: libOSMesa and GLVND's libOpenGL both export gl* symbols that dispatch only to their own
// contexts, so a binary with both backends cannot call GL directly (docs/platform-notes.md: linking
// -lGL beside OSMesa crashed). Include this instead of <GL/gl.h>: each glFoo below becomes a call
// through the table of the context current on this thread.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES  // the prototypes give the pointer types (decltype); never linked
#endif
#include <GL/gl.h>
#include <GL/glext.h>

// Every GL function the project calls (render/*.cpp and imgui_impl_opengl3.cpp).
// clang-format off
#define SPINFOLD_GL_FUNCTIONS(X) \
  X(glActiveTexture) X(glAttachShader) X(glBindBuffer) X(glBindFramebuffer) X(glBindRenderbuffer) \
  X(glBindSampler) X(glBindTexture) X(glBindVertexArray) X(glBlendEquation) \
  X(glBlendEquationSeparate) X(glBlendFunc) X(glBlendFuncSeparate) X(glBlitFramebuffer) \
  X(glBufferData) X(glBufferSubData) X(glCheckFramebufferStatus) X(glClear) X(glClearColor) \
  X(glClipControl) X(glCompileShader) X(glCopyImageSubData) X(glCreateProgram) X(glCreateShader) \
  X(glDeleteBuffers) X(glDeleteFramebuffers) X(glDeleteProgram) X(glDeleteRenderbuffers) \
  X(glDeleteShader) X(glDeleteTextures) X(glDeleteVertexArrays) X(glDepthFunc) X(glDepthMask) \
  X(glDetachShader) X(glDisable) X(glDisableVertexAttribArray) X(glDrawArrays) \
  X(glDrawArraysInstanced) X(glDrawElements) X(glDrawElementsBaseVertex) X(glEnable) X(glEnableVertexAttribArray) X(glFinish) \
  X(glFramebufferRenderbuffer) X(glGenBuffers) X(glGenFramebuffers) X(glGenRenderbuffers) \
  X(glGenTextures) X(glGenVertexArrays) X(glGetAttribLocation) X(glGetError) X(glGetIntegerv) \
  X(glGetProgramInfoLog) X(glGetProgramiv) X(glGetShaderInfoLog) X(glGetShaderiv) X(glGetString) \
  X(glGetStringi) X(glGetUniformLocation) X(glIsEnabled) X(glLineWidth) X(glLinkProgram) \
  X(glPixelStorei) X(glPolygonMode) X(glReadPixels) X(glRenderbufferStorageMultisample) \
  X(glScissor) X(glShaderSource) X(glTexImage2D) X(glTexParameteri) X(glUniform1f) X(glUniform1i) \
  X(glUniform2f) X(glUniform3fv) X(glUniform4fv) X(glUniformMatrix4fv) X(glUseProgram) \
  X(glVertexAttribDivisor) X(glVertexAttribPointer) X(glViewport)
// clang-format on

namespace spinfold::render {

struct GlApi {
#define SPINFOLD_GL_MEMBER(name) decltype(&::name) fn_##name = nullptr;
  SPINFOLD_GL_FUNCTIONS(SPINFOLD_GL_MEMBER)
#undef SPINFOLD_GL_MEMBER

  // Looks every function up; throws std::runtime_error naming the first one missing.
  using ProcLookup = void (*(*)(const char*))();
  static GlApi load(ProcLookup lookup);
};

// The table of the context current on this thread (set by GlContext::make_current), or null.
const GlApi* current_gl_api();
void set_current_gl_api(const GlApi* api);

}  // namespace spinfold::render

// From here on, glFoo(...) calls through the current table (a null table crashes, as calling GL
// without a current context may).
#define glActiveTexture (::spinfold::render::current_gl_api()->fn_glActiveTexture)
#define glAttachShader (::spinfold::render::current_gl_api()->fn_glAttachShader)
#define glBindBuffer (::spinfold::render::current_gl_api()->fn_glBindBuffer)
#define glBindFramebuffer (::spinfold::render::current_gl_api()->fn_glBindFramebuffer)
#define glBindRenderbuffer (::spinfold::render::current_gl_api()->fn_glBindRenderbuffer)
#define glBindSampler (::spinfold::render::current_gl_api()->fn_glBindSampler)
#define glBindTexture (::spinfold::render::current_gl_api()->fn_glBindTexture)
#define glBindVertexArray (::spinfold::render::current_gl_api()->fn_glBindVertexArray)
#define glBlendEquation (::spinfold::render::current_gl_api()->fn_glBlendEquation)
#define glBlendEquationSeparate (::spinfold::render::current_gl_api()->fn_glBlendEquationSeparate)
#define glBlendFunc (::spinfold::render::current_gl_api()->fn_glBlendFunc)
#define glBlendFuncSeparate (::spinfold::render::current_gl_api()->fn_glBlendFuncSeparate)
#define glBlitFramebuffer (::spinfold::render::current_gl_api()->fn_glBlitFramebuffer)
#define glBufferData (::spinfold::render::current_gl_api()->fn_glBufferData)
#define glBufferSubData (::spinfold::render::current_gl_api()->fn_glBufferSubData)
#define glCheckFramebufferStatus (::spinfold::render::current_gl_api()->fn_glCheckFramebufferStatus)
#define glClear (::spinfold::render::current_gl_api()->fn_glClear)
#define glClearColor (::spinfold::render::current_gl_api()->fn_glClearColor)
#define glClipControl (::spinfold::render::current_gl_api()->fn_glClipControl)
#define glCompileShader (::spinfold::render::current_gl_api()->fn_glCompileShader)
#define glCopyImageSubData (::spinfold::render::current_gl_api()->fn_glCopyImageSubData)
#define glCreateProgram (::spinfold::render::current_gl_api()->fn_glCreateProgram)
#define glCreateShader (::spinfold::render::current_gl_api()->fn_glCreateShader)
#define glDeleteBuffers (::spinfold::render::current_gl_api()->fn_glDeleteBuffers)
#define glDeleteFramebuffers (::spinfold::render::current_gl_api()->fn_glDeleteFramebuffers)
#define glDeleteProgram (::spinfold::render::current_gl_api()->fn_glDeleteProgram)
#define glDeleteRenderbuffers (::spinfold::render::current_gl_api()->fn_glDeleteRenderbuffers)
#define glDeleteShader (::spinfold::render::current_gl_api()->fn_glDeleteShader)
#define glDeleteTextures (::spinfold::render::current_gl_api()->fn_glDeleteTextures)
#define glDeleteVertexArrays (::spinfold::render::current_gl_api()->fn_glDeleteVertexArrays)
#define glDepthFunc (::spinfold::render::current_gl_api()->fn_glDepthFunc)
#define glDepthMask (::spinfold::render::current_gl_api()->fn_glDepthMask)
#define glDetachShader (::spinfold::render::current_gl_api()->fn_glDetachShader)
#define glDisable (::spinfold::render::current_gl_api()->fn_glDisable)
#define glDisableVertexAttribArray (::spinfold::render::current_gl_api()->fn_glDisableVertexAttribArray)
#define glDrawArrays (::spinfold::render::current_gl_api()->fn_glDrawArrays)
#define glDrawArraysInstanced (::spinfold::render::current_gl_api()->fn_glDrawArraysInstanced)
#define glDrawElements (::spinfold::render::current_gl_api()->fn_glDrawElements)
#define glDrawElementsBaseVertex (::spinfold::render::current_gl_api()->fn_glDrawElementsBaseVertex)
#define glEnable (::spinfold::render::current_gl_api()->fn_glEnable)
#define glEnableVertexAttribArray (::spinfold::render::current_gl_api()->fn_glEnableVertexAttribArray)
#define glFinish (::spinfold::render::current_gl_api()->fn_glFinish)
#define glFramebufferRenderbuffer (::spinfold::render::current_gl_api()->fn_glFramebufferRenderbuffer)
#define glGenBuffers (::spinfold::render::current_gl_api()->fn_glGenBuffers)
#define glGenFramebuffers (::spinfold::render::current_gl_api()->fn_glGenFramebuffers)
#define glGenRenderbuffers (::spinfold::render::current_gl_api()->fn_glGenRenderbuffers)
#define glGenTextures (::spinfold::render::current_gl_api()->fn_glGenTextures)
#define glGenVertexArrays (::spinfold::render::current_gl_api()->fn_glGenVertexArrays)
#define glGetAttribLocation (::spinfold::render::current_gl_api()->fn_glGetAttribLocation)
#define glGetError (::spinfold::render::current_gl_api()->fn_glGetError)
#define glGetIntegerv (::spinfold::render::current_gl_api()->fn_glGetIntegerv)
#define glGetProgramInfoLog (::spinfold::render::current_gl_api()->fn_glGetProgramInfoLog)
#define glGetProgramiv (::spinfold::render::current_gl_api()->fn_glGetProgramiv)
#define glGetShaderInfoLog (::spinfold::render::current_gl_api()->fn_glGetShaderInfoLog)
#define glGetShaderiv (::spinfold::render::current_gl_api()->fn_glGetShaderiv)
#define glGetString (::spinfold::render::current_gl_api()->fn_glGetString)
#define glGetStringi (::spinfold::render::current_gl_api()->fn_glGetStringi)
#define glGetUniformLocation (::spinfold::render::current_gl_api()->fn_glGetUniformLocation)
#define glIsEnabled (::spinfold::render::current_gl_api()->fn_glIsEnabled)
#define glLineWidth (::spinfold::render::current_gl_api()->fn_glLineWidth)
#define glLinkProgram (::spinfold::render::current_gl_api()->fn_glLinkProgram)
#define glPixelStorei (::spinfold::render::current_gl_api()->fn_glPixelStorei)
#define glPolygonMode (::spinfold::render::current_gl_api()->fn_glPolygonMode)
#define glReadPixels (::spinfold::render::current_gl_api()->fn_glReadPixels)
#define glRenderbufferStorageMultisample \
  (::spinfold::render::current_gl_api()->fn_glRenderbufferStorageMultisample)
#define glScissor (::spinfold::render::current_gl_api()->fn_glScissor)
#define glShaderSource (::spinfold::render::current_gl_api()->fn_glShaderSource)
#define glTexImage2D (::spinfold::render::current_gl_api()->fn_glTexImage2D)
#define glTexParameteri (::spinfold::render::current_gl_api()->fn_glTexParameteri)
#define glUniform1f (::spinfold::render::current_gl_api()->fn_glUniform1f)
#define glUniform1i (::spinfold::render::current_gl_api()->fn_glUniform1i)
#define glUniform2f (::spinfold::render::current_gl_api()->fn_glUniform2f)
#define glUniform3fv (::spinfold::render::current_gl_api()->fn_glUniform3fv)
#define glUniform4fv (::spinfold::render::current_gl_api()->fn_glUniform4fv)
#define glUniformMatrix4fv (::spinfold::render::current_gl_api()->fn_glUniformMatrix4fv)
#define glUseProgram (::spinfold::render::current_gl_api()->fn_glUseProgram)
#define glVertexAttribDivisor (::spinfold::render::current_gl_api()->fn_glVertexAttribDivisor)
#define glVertexAttribPointer (::spinfold::render::current_gl_api()->fn_glVertexAttribPointer)
#define glViewport (::spinfold::render::current_gl_api()->fn_glViewport)
