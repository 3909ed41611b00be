#include "render/triangle_renderer.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <cmath>
#include <string>

#include "render/headless_gl.hpp"

namespace frontsteal::render {

namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
  world_position = position;
  world_normal = normal;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

// Two-sided Lambert with a head light: open surfaces and trimmed holes show their back faces too.
constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
uniform vec3 eye;
uniform vec3 colour;
out vec4 fragment;
void main() {
  vec3 n = normalize(world_normal);
  vec3 l = normalize(eye - world_position);
  float shade = 0.25 + 0.75 * abs(dot(n, l));
  fragment = vec4(colour * shade, 1.0);
}
)";

unsigned compile(GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw GraphicsError(std::string("OpenGL shader compilation failed: ") + log);
  }
  return shader;
}

// A stable, well-spread colour per component (golden-ratio hue steps), light enough to shade.
glm::vec3 component_colour(std::uint32_t c) {
  const double h = std::fmod(0.13 + 0.618033988749895 * c, 1.0) * 6.0;
  const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
  glm::dvec3 rgb = h < 1   ? glm::dvec3(1, x, 0)
                   : h < 2 ? glm::dvec3(x, 1, 0)
                   : h < 3 ? glm::dvec3(0, 1, x)
                   : h < 4 ? glm::dvec3(0, x, 1)
                   : h < 5 ? glm::dvec3(x, 0, 1)
                           : glm::dvec3(1, 0, x);
  return glm::vec3(0.35 + 0.6 * rgb);
}

}  // namespace

TriangleRenderer::TriangleRenderer(std::uint32_t components) : meshes_(components) {
  const unsigned vs = compile(GL_VERTEX_SHADER, kVertexShader);
  const unsigned fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw GraphicsError("OpenGL program link failed");
  view_projection_location_ = glGetUniformLocation(program_, "view_projection");
  eye_location_ = glGetUniformLocation(program_, "eye");
  colour_location_ = glGetUniformLocation(program_, "colour");
  glEnable(GL_DEPTH_TEST);
}

TriangleRenderer::~TriangleRenderer() {
  for (Mesh& m : meshes_) {
    if (m.vao == 0) continue;
    glDeleteVertexArrays(1, &m.vao);
    glDeleteBuffers(1, &m.vertices);
    glDeleteBuffers(1, &m.indices);
  }
  glDeleteProgram(program_);
}

void TriangleRenderer::upload(std::uint32_t c, std::span<const tess::TriangleBuffers* const> surfaces) {
  Mesh& m = meshes_.at(c);
  if (m.vao == 0) {
    glGenVertexArrays(1, &m.vao);
    glGenBuffers(1, &m.vertices);
    glGenBuffers(1, &m.indices);
    glBindVertexArray(m.vao);
    glBindBuffer(GL_ARRAY_BUFFER, m.vertices);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.indices);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  }
  vertex_scratch_.clear();
  index_scratch_.clear();
  for (const tess::TriangleBuffers* s : surfaces) {
    if (s == nullptr) continue;
    const auto base = static_cast<std::uint32_t>(vertex_scratch_.size() / 6);
    for (std::size_t v = 0; v < s->positions.size(); ++v) {
      const glm::vec3& p = s->positions[v];
      const glm::vec3& n = s->normals[v];
      vertex_scratch_.insert(vertex_scratch_.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    for (std::uint32_t i : s->indices) index_scratch_.push_back(base + i);
  }
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vertices);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertex_scratch_.size() * sizeof(float)), vertex_scratch_.data(),
               GL_DYNAMIC_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(index_scratch_.size() * sizeof(std::uint32_t)),
               index_scratch_.data(), GL_DYNAMIC_DRAW);
  m.index_count = index_scratch_.size();
}

void TriangleRenderer::begin_frame(const glm::dmat4& view_projection, const glm::dvec3& eye) {
  glClearColor(kBackground[0] / 255.0f, kBackground[1] / 255.0f, kBackground[2] / 255.0f, 1.0f);
  // Depth test on every frame, not only at construction: in a window the overlay (Dear ImGui) shares the context.
  glEnable(GL_DEPTH_TEST);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glUseProgram(program_);
  const glm::mat4 vp(view_projection);
  glUniformMatrix4fv(view_projection_location_, 1, GL_FALSE, &vp[0][0]);
  glUniform3f(eye_location_, static_cast<float>(eye.x), static_cast<float>(eye.y), static_cast<float>(eye.z));
}

std::uint64_t TriangleRenderer::draw(std::uint32_t c) {
  const Mesh& m = meshes_.at(c);
  if (m.index_count == 0) return 0;
  const glm::vec3 colour = component_colour(c);
  glUniform3f(colour_location_, colour.x, colour.y, colour.z);
  glBindVertexArray(m.vao);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(m.index_count), GL_UNSIGNED_INT, nullptr);
  return m.index_count / 3;
}

void TriangleRenderer::finish() const { glFinish(); }

Image TriangleRenderer::read_pixels(int width, int height) const { return read_framebuffer(width, height); }

Image read_framebuffer(int width, int height) {
  Image image(width, height);
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* src = &rgba[(static_cast<std::size_t>(height - 1 - y) * width + x) * 4];
      std::uint8_t* dst = &image.rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      dst[0] = src[0];
      dst[1] = src[1];
      dst[2] = src[2];
    }
  }
  return image;
}

}  // namespace frontsteal::render
