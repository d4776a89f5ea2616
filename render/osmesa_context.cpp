// OSMesa: Mesa's off-screen software renderer into a caller-owned RGBA buffer.
#include <GL/osmesa.h>

#include <vector>

#include "render/gl_context.hpp"

namespace lifelong::render {
namespace {

class OsMesaGl : public GlContext {
 public:
  OsMesaGl(OSMesaContext context, int width, int height)
      : context_(context),
        width_(width),
        height_(height),
        buffer_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4u) {}
  ~OsMesaGl() override { OSMesaDestroyContext(context_); }
  OsMesaGl(const OsMesaGl&) = delete;
  OsMesaGl& operator=(const OsMesaGl&) = delete;

  bool MakeCurrent() override {
    return OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_) ==
           GL_TRUE;
  }
  void Release() override { OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0); }
  GlProc GetProc(const char* name) const override {
    return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
  }
  Backend backend() const override { return Backend::kOsMesa; }
  std::string device() const override { return "software"; }

 private:
  OSMesaContext context_;
  int width_, height_;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> CreateOsMesaContext(int width, int height, std::string* error) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_COMPAT_PROFILE,
                         0};
  OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (context == nullptr) {
    *error = "OSMesa: OSMesaCreateContextAttribs failed";
    return nullptr;
  }
  auto out = std::make_unique<OsMesaGl>(context, width, height);
  if (!out->MakeCurrent()) {
    *error = "OSMesa: OSMesaMakeCurrent failed for " + std::to_string(width) + "x" +
             std::to_string(height);
    return nullptr;
  }
  out->Release();
  return out;
}

}  // namespace lifelong::render
