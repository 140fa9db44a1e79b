#include "egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace shadowlab {
namespace {

void check(bool ok, const std::string& step) {
  if (!ok) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", unsigned(eglGetError()));
    throw std::runtime_error("EGL: " + step + " failed (error " + code + ")");
  }
}

}  // namespace

EglContext make_llvmpipe_context() {
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);  // the software path: llvmpipe, never a GPU
  EglContext c;
  EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                         nullptr);
  check(dpy != EGL_NO_DISPLAY, "eglGetPlatformDisplay(surfaceless)");
  EGLint major = 0, minor = 0;
  check(eglInitialize(dpy, &major, &minor), "eglInitialize");
  c.display = dpy;
  check(eglBindAPI(EGL_OPENGL_API), "eglBindAPI(OpenGL)");
  // No surface is ever drawn to (the cube is framebuffer objects), so no config is needed.
  const std::string extensions = eglQueryString(dpy, EGL_EXTENSIONS);
  check(extensions.find("EGL_KHR_no_config_context") != std::string::npos &&
            extensions.find("EGL_KHR_surfaceless_context") != std::string::npos,
        "finding EGL_KHR_no_config_context and EGL_KHR_surfaceless_context");
  const EGLConfig config = EGL_NO_CONFIG_KHR;
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, context_attribs);
  check(ctx != EGL_NO_CONTEXT, "eglCreateContext(OpenGL 4.5 core)");
  c.context = ctx;
  check(eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx), "eglMakeCurrent(surfaceless)");
  c.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  c.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (c.renderer.find("llvmpipe") == std::string::npos)
    throw std::runtime_error("EGL: the renderer is '" + c.renderer + "', not llvmpipe");
  return c;
}

void destroy_context(EglContext& c) {
  if (!c.display) return;
  eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (c.context) eglDestroyContext(c.display, c.context);
  eglTerminate(c.display);
  c = EglContext{};
}

}  // namespace shadowlab
