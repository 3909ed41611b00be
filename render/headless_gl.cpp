#include "render/headless_gl.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstring>

namespace frontsteal::render {

namespace {

[[noreturn]] void fail(const std::string& step) {
  char code[32];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  throw GraphicsError("headless OpenGL: " + step + " failed (EGL error " + code +
                      "); Debian packages libegl1, libegl-mesa0 and libgl1-mesa-dri provide Mesa's EGL");
}

// The surfaceless platform when Mesa offers it (no display server, no GPU needed), else the default display.
EGLDisplay open_display() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (client != nullptr && std::strstr(client, "EGL_MESA_platform_surfaceless") != nullptr && get_platform_display) {
    EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) return d;
  }
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

}  // namespace

HeadlessGL::HeadlessGL(int width, int height, GLVersion version) : width_(width), height_(height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384) {
    throw GraphicsError("headless OpenGL: image size " + std::to_string(width) + "x" + std::to_string(height) +
                        " is out of range (1..16384)");
  }
  EGLDisplay display = open_display();
  if (display == EGL_NO_DISPLAY) fail("eglGetDisplay");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) fail("eglInitialize");
  display_ = display;
  const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  // Surfaceless: any config that renders OpenGL will do (we draw into our own framebuffer object).
  if (!eglChooseConfig(display, config_attributes, &config, 1, &configs)) fail("eglChooseConfig");
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(OpenGL)");
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                       version.major,
                                       EGL_CONTEXT_MINOR_VERSION,
                                       version.minor,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  EGLContext context =
      eglCreateContext(display, configs > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) {
    fail("eglCreateContext (OpenGL " + std::to_string(version.major) + "." + std::to_string(version.minor) + " core)");
  }
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) fail("eglMakeCurrent (surfaceless)");

  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glGenRenderbuffers(1, &colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GraphicsError("headless OpenGL: the framebuffer object is incomplete");
  }
  glViewport(0, 0, width, height);
  description_ = std::string(reinterpret_cast<const char*>(glGetString(GL_VENDOR))) + ", " +
                 reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ", OpenGL " +
                 reinterpret_cast<const char*>(glGetString(GL_VERSION)) + ", EGL " + std::to_string(major) + "." +
                 std::to_string(minor);
  release();
}

HeadlessGL::~HeadlessGL() {
  if (display_ == nullptr) return;
  if (context_ != nullptr && eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
    glDeleteRenderbuffers(1, &colour_);
    glDeleteRenderbuffers(1, &depth_);
    glDeleteFramebuffers(1, &framebuffer_);
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (context_ != nullptr) eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

void HeadlessGL::make_current() {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) fail("eglMakeCurrent");
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, width_, height_);
}

void HeadlessGL::release() { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

}  // namespace frontsteal::render
