#pragma once
// An OpenGL 4.5 core context on Mesa's llvmpipe without a window: EGL's surfaceless platform
// (EGL_MESA_platform_surfaceless) with the software rasterizer forced (LIBGL_ALWAYS_SOFTWARE),
// so the driver is llvmpipe on any machine, with or without a GPU.
#include <string>

namespace shadowlab {

struct EglContext {
  void* display = nullptr;  // EGLDisplay
  void* context = nullptr;  // EGLContext
  std::string renderer;     // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version;      // GL_VERSION
};

// Creates the context and makes it current on this thread; std::runtime_error naming the
// step that failed, or when the renderer is not llvmpipe. LP_NUM_THREADS (llvmpipe's
// rasterizer threads) must be set before the call.
EglContext make_llvmpipe_context();

void destroy_context(EglContext& c);

}  // namespace shadowlab
