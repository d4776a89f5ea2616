// EGL without a window system: a device display (EGL_EXT_platform_device; devices that
// are not Mesa's software device first) or Mesa's surfaceless platform, a desktop-GL
// compatibility context made current without a surface (EGL_KHR_surfaceless_context,
// else on a 1x1 pbuffer), drawing into a framebuffer object of the requested size.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstring>
#include <vector>

#include "render/gl_context.hpp"

namespace lifelong::render {
namespace {

template <typename F>
F EglProc(const char* name) {
  return reinterpret_cast<F>(eglGetProcAddress(name));
}

bool HasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name)) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

struct Candidate {
  EGLDisplay display;
  Backend backend;
  std::string device;
};

// Device displays (hardware first), then the surfaceless platform.
std::vector<Candidate> Displays() {
  std::vector<Candidate> out;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_display = EglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (get_display == nullptr) return out;
  auto query_devices = EglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto device_string = EglProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  if (HasExtension(client, "EGL_EXT_platform_device") && query_devices && device_string) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices(16, devices, &count) == EGL_TRUE) {
      std::vector<Candidate> software;
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d == EGL_NO_DISPLAY) continue;
        const bool sw =
            HasExtension(device_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software");
        (sw ? software : out).push_back({d, Backend::kEglDevice, sw ? "software" : "hardware"});
      }
      out.insert(out.end(), software.begin(), software.end());
    }
  }
  if (HasExtension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back({d, Backend::kEglSurfaceless, ""});
  }
  return out;
}

class EglGl : public GlContext {
 public:
  EglGl(const Candidate& c, EGLContext context, EGLSurface surface)
      : candidate_(c), context_(context), surface_(surface) {}
  ~EglGl() override {
    if (fbo_ != 0 && MakeCurrent()) {
      EglProc<PFNGLDELETEFRAMEBUFFERSPROC>("glDeleteFramebuffers")(1, &fbo_);
      EglProc<PFNGLDELETERENDERBUFFERSPROC>("glDeleteRenderbuffers")(1, &colour_);
      Release();
    }
    eglDestroyContext(candidate_.display, context_);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(candidate_.display, surface_);
  }
  EglGl(const EglGl&) = delete;
  EglGl& operator=(const EglGl&) = delete;

  bool MakeCurrent() override {
    if (eglMakeCurrent(candidate_.display, surface_, surface_, context_) != EGL_TRUE) return false;
    if (fbo_ != 0) bind_fb_(GL_FRAMEBUFFER, fbo_);
    return true;
  }
  void Release() override {
    eglMakeCurrent(candidate_.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  GlProc GetProc(const char* name) const override { return eglGetProcAddress(name); }
  Backend backend() const override { return candidate_.backend; }
  std::string device() const override { return candidate_.device; }

  // Called once, current: a framebuffer object with an RGBA8 colour renderbuffer.
  bool MakeTarget(int width, int height) {
    auto gen_fb = EglProc<PFNGLGENFRAMEBUFFERSPROC>("glGenFramebuffers");
    auto gen_rb = EglProc<PFNGLGENRENDERBUFFERSPROC>("glGenRenderbuffers");
    auto bind_rb = EglProc<PFNGLBINDRENDERBUFFERPROC>("glBindRenderbuffer");
    auto storage = EglProc<PFNGLRENDERBUFFERSTORAGEPROC>("glRenderbufferStorage");
    auto attach = EglProc<PFNGLFRAMEBUFFERRENDERBUFFERPROC>("glFramebufferRenderbuffer");
    auto status = EglProc<PFNGLCHECKFRAMEBUFFERSTATUSPROC>("glCheckFramebufferStatus");
    bind_fb_ = EglProc<PFNGLBINDFRAMEBUFFERPROC>("glBindFramebuffer");
    if (!gen_fb || !gen_rb || !bind_rb || !storage || !attach || !status || !bind_fb_) return false;
    gen_fb(1, &fbo_);
    gen_rb(1, &colour_);
    bind_rb(GL_RENDERBUFFER, colour_);
    storage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    bind_fb_(GL_FRAMEBUFFER, fbo_);
    attach(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    return status(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  }

 private:
  Candidate candidate_;
  EGLContext context_;
  EGLSurface surface_;
  GLuint fbo_ = 0, colour_ = 0;
  PFNGLBINDFRAMEBUFFERPROC bind_fb_ = nullptr;
};

std::unique_ptr<EglGl> TryDisplay(const Candidate& c, int width, int height, std::string* why) {
  EGLint major = 0, minor = 0;
  if (eglInitialize(c.display, &major, &minor) != EGL_TRUE) return *why = "eglInitialize", nullptr;
  const EGLint attribs[] = {EGL_SURFACE_TYPE,
                            EGL_PBUFFER_BIT,
                            EGL_RENDERABLE_TYPE,
                            EGL_OPENGL_BIT,
                            EGL_RED_SIZE,
                            8,
                            EGL_GREEN_SIZE,
                            8,
                            EGL_BLUE_SIZE,
                            8,
                            EGL_NONE};
  EGLConfig config = nullptr;
  EGLint n = 0;
  if (eglChooseConfig(c.display, attribs, &config, 1, &n) != EGL_TRUE || n < 1)
    return *why = "no desktop-GL config", nullptr;
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) return *why = "eglBindAPI(OpenGL)", nullptr;
  EGLContext context = eglCreateContext(c.display, config, EGL_NO_CONTEXT, nullptr);
  if (context == EGL_NO_CONTEXT) return *why = "eglCreateContext", nullptr;
  EGLSurface surface = EGL_NO_SURFACE;
  if (!HasExtension(eglQueryString(c.display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
    const EGLint pbuffer[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface = eglCreatePbufferSurface(c.display, config, pbuffer);
  }
  auto out = std::make_unique<EglGl>(c, context, surface);
  if (!out->MakeCurrent()) return *why = "eglMakeCurrent", nullptr;
  const bool ok = out->MakeTarget(width, height);
  out->Release();
  if (!ok) return *why = "framebuffer object incomplete", nullptr;
  return out;
}

}  // namespace

std::unique_ptr<GlContext> CreateEglContext(int width, int height, std::string* error) {
  std::string reasons;
  for (const Candidate& c : Displays()) {
    std::string why;
    if (auto gl = TryDisplay(c, width, height, &why)) return gl;
    reasons += std::string(reasons.empty() ? "" : "; ") + BackendName(c.backend) + ": " + why;
  }
  *error = "EGL: " + (reasons.empty() ? std::string("no device or surfaceless display") : reasons);
  return nullptr;
}

const char* BackendName(Backend backend) {
  switch (backend) {
    case Backend::kEglDevice:
      return "egl-device";
    case Backend::kEglSurfaceless:
      return "egl-surfaceless";
    case Backend::kOsMesa:
      return "osmesa";
  }
  return "unknown";
}

}  // namespace lifelong::render
