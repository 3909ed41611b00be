// headless_gl.hpp — an OpenGL core context without a window: EGL, surfaceless, rendering into a framebuffer
// object. 3.3 by default (what drawing needs); 4.3 for compute shaders (gpu_patch_tessellator.hpp). On machines without
// a GPU, Mesa's EGL gives llvmpipe (OpenGL 4.5); on a GPU machine the same code gets the vendor's EGL through libglvnd.
//
// The context is current on one thread at a time: make_current() on the thread that draws (the pusher), and
// release() before another thread makes it current (the synchronized reference renders after a run).
#pragma once

#include <stdexcept>
#include <string>

namespace frontsteal::render {

// EGL or OpenGL could not be set up; what() says which step failed and the EGL error.
struct GraphicsError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The OpenGL core version a context is asked for.
struct GLVersion {
  int major = 3, minor = 3;
};

class HeadlessGL {
 public:
  // Creates the context and a width × height colour + depth framebuffer.
  HeadlessGL(int width, int height, GLVersion version = {});
  ~HeadlessGL();
  HeadlessGL(const HeadlessGL&) = delete;
  HeadlessGL& operator=(const HeadlessGL&) = delete;

  void make_current();  // and binds the framebuffer
  void release();
  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  const std::string& description() const noexcept { return description_; }  // vendor, renderer, version

 private:
  int width_, height_;
  void* display_ = nullptr;
  void* context_ = nullptr;
  unsigned framebuffer_ = 0, colour_ = 0, depth_ = 0;
  std::string description_;
};

}  // namespace frontsteal::render
