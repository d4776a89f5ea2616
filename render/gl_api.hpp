// The fixed-function GL 1.x entry points the renderer uses, looked up through the
// context's backend (see gl_context.hpp) instead of linked. Internal to render.
#pragma once

#include <GL/gl.h>

#include "render/gl_context.hpp"

namespace lifelong::render {

struct GlApi {
  decltype(&::glViewport) Viewport = nullptr;
  decltype(&::glScissor) Scissor = nullptr;
  decltype(&::glEnable) Enable = nullptr;
  decltype(&::glDisable) Disable = nullptr;
  decltype(&::glClearColor) ClearColor = nullptr;
  decltype(&::glClear) Clear = nullptr;
  decltype(&::glMatrixMode) MatrixMode = nullptr;
  decltype(&::glLoadIdentity) LoadIdentity = nullptr;
  decltype(&::glOrtho) Ortho = nullptr;
  decltype(&::glColor3ub) Color3ub = nullptr;
  decltype(&::glLineWidth) LineWidth = nullptr;
  decltype(&::glPointSize) PointSize = nullptr;
  decltype(&::glEnableClientState) EnableClientState = nullptr;
  decltype(&::glDisableClientState) DisableClientState = nullptr;
  decltype(&::glVertexPointer) VertexPointer = nullptr;
  decltype(&::glTexCoordPointer) TexCoordPointer = nullptr;
  decltype(&::glDrawArrays) DrawArrays = nullptr;
  decltype(&::glGenTextures) GenTextures = nullptr;
  decltype(&::glDeleteTextures) DeleteTextures = nullptr;
  decltype(&::glBindTexture) BindTexture = nullptr;
  decltype(&::glTexParameteri) TexParameteri = nullptr;
  decltype(&::glTexImage2D) TexImage2D = nullptr;
  decltype(&::glTexEnvi) TexEnvi = nullptr;
  decltype(&::glPixelStorei) PixelStorei = nullptr;
  decltype(&::glReadPixels) ReadPixels = nullptr;
  decltype(&::glGetIntegerv) GetIntegerv = nullptr;
  decltype(&::glGetError) GetError = nullptr;
  decltype(&::glFinish) Finish = nullptr;

  /// Looks every entry point up; false (naming the first missing one) if one is absent.
  bool Load(const GlContext& context, std::string* missing);
};

}  // namespace lifelong::render
