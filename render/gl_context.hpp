// An offscreen OpenGL compatibility context (fixed-function GL works) with a colour target
// of a fixed size, created without any display: EGL on a device (EGL_EXT_platform_device,
// a GPU first, else Mesa's software device) or on EGL_MESA_platform_surfaceless, drawing
// into a framebuffer object; or OSMesa, drawing into a buffer in memory. GL functions are
// looked up through the backend (eglGetProcAddress / OSMesaGetProcAddress), never linked,
// so EGL's and OSMesa's dispatch never mix. Internal to render.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace lifelong::render {

enum class Backend : std::uint8_t {
  kEglDevice,       ///< EGL on a device (hardware if present)
  kEglSurfaceless,  ///< EGL on Mesa's surfaceless platform
  kOsMesa,          ///< OSMesa software rendering
};

/// Which backends Create may try, in the order EGL then OSMesa.
enum class BackendChoice : std::uint8_t { kAuto, kEglOnly, kOsMesaOnly };

const char* BackendName(Backend backend);

using GlProc = void (*)();

class GlContext {
 public:
  virtual ~GlContext() = default;
  /// Binds the context and its colour target to the calling thread; false on failure.
  virtual bool MakeCurrent() = 0;
  /// Unbinds it, so another backend's context can be made current next.
  virtual void Release() = 0;
  virtual GlProc GetProc(const char* name) const = 0;
  virtual Backend backend() const = 0;
  /// "hardware" or "software" where the backend says, else empty.
  virtual std::string device() const = 0;
};

/// Each returns nullptr and sets *error when it cannot make a context.
std::unique_ptr<GlContext> CreateEglContext(int width, int height, std::string* error);
std::unique_ptr<GlContext> CreateOsMesaContext(int width, int height, std::string* error);

}  // namespace lifelong::render
