// triangle_renderer.hpp — draws per-component triangle meshes with OpenGL 3.3 core (one vertex and index
// buffer per component, replaced whole when the component's published triangles change), Lambert shading with
// a head light, one colour per component, and reads the image back.
//
// Needs a current OpenGL 3.3 core context on the calling thread for every call, the destructor too: HeadlessGL's
// (EGL, its framebuffer object bound by make_current) or a window's (frontsteal-view: GLFW, the default
// framebuffer). It draws into whatever framebuffer and viewport are bound; read_pixels reads the bound one.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/image.hpp"
#include "tessellate/grid_tessellator.hpp"

namespace frontsteal::render {

class TriangleRenderer {
 public:
  static constexpr std::uint8_t kBackground[3] = {24, 26, 30};

  explicit TriangleRenderer(std::uint32_t components);
  ~TriangleRenderer();
  TriangleRenderer(const TriangleRenderer&) = delete;
  TriangleRenderer& operator=(const TriangleRenderer&) = delete;

  // Replaces component c's mesh by the triangles of these surfaces (null entries: nothing).
  void upload(std::uint32_t c, std::span<const tess::TriangleBuffers* const> surfaces);
  // Clears the image and sets the camera for the draws that follow.
  void begin_frame(const glm::dmat4& view_projection, const glm::dvec3& eye);
  // Draws component c's current mesh; returns its triangle count.
  std::uint64_t draw(std::uint32_t c);
  // Waits for the draws and returns the image (rows top to bottom).
  Image read_pixels(int width, int height) const;
  void finish() const;  // waits for the GPU (or llvmpipe) to finish the draws: honest update timings

 private:
  struct Mesh {
    unsigned vao = 0, vertices = 0, indices = 0;
    std::uint64_t index_count = 0;
  };
  std::vector<Mesh> meshes_;
  unsigned program_ = 0;
  int view_projection_location_ = -1, eye_location_ = -1, colour_location_ = -1;
  std::vector<float> vertex_scratch_;
  std::vector<std::uint32_t> index_scratch_;
};

// The bound framebuffer's lower-left width × height pixels (rows top to bottom): what a window shows, overlay
// included, when called before the buffer swap. Needs a current context.
Image read_framebuffer(int width, int height);

}  // namespace frontsteal::render
