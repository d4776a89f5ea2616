#include "render/gl_api.hpp"

#include <string>

namespace lifelong::render {
namespace {

template <typename F>
bool Get(const GlContext& context, const char* name, F* out, std::string* missing) {
  *out = reinterpret_cast<F>(context.GetProc(name));
  if (*out == nullptr && missing->empty()) *missing = name;
  return *out != nullptr;
}

}  // namespace

bool GlApi::Load(const GlContext& c, std::string* missing) {
  missing->clear();
  Get(c, "glViewport", &Viewport, missing), Get(c, "glScissor", &Scissor, missing);
  Get(c, "glEnable", &Enable, missing), Get(c, "glDisable", &Disable, missing);
  Get(c, "glClearColor", &ClearColor, missing), Get(c, "glClear", &Clear, missing);
  Get(c, "glMatrixMode", &MatrixMode, missing), Get(c, "glLoadIdentity", &LoadIdentity, missing);
  Get(c, "glOrtho", &Ortho, missing), Get(c, "glColor3ub", &Color3ub, missing);
  Get(c, "glLineWidth", &LineWidth, missing), Get(c, "glPointSize", &PointSize, missing);
  Get(c, "glEnableClientState", &EnableClientState, missing);
  Get(c, "glDisableClientState", &DisableClientState, missing);
  Get(c, "glVertexPointer", &VertexPointer, missing);
  Get(c, "glTexCoordPointer", &TexCoordPointer, missing);
  Get(c, "glDrawArrays", &DrawArrays, missing), Get(c, "glGenTextures", &GenTextures, missing);
  Get(c, "glDeleteTextures", &DeleteTextures, missing);
  Get(c, "glBindTexture", &BindTexture, missing);
  Get(c, "glTexParameteri", &TexParameteri, missing);
  Get(c, "glTexImage2D", &TexImage2D, missing), Get(c, "glTexEnvi", &TexEnvi, missing);
  Get(c, "glPixelStorei", &PixelStorei, missing), Get(c, "glReadPixels", &ReadPixels, missing);
  Get(c, "glGetIntegerv", &GetIntegerv, missing), Get(c, "glGetError", &GetError, missing);
  Get(c, "glFinish", &Finish, missing);
  return missing->empty();
}

}  // namespace lifelong::render
