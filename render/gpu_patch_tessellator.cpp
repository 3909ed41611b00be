#include "render/gpu_patch_tessellator.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/headless_gl.hpp"
#include "tessellate/grid_row_kernel.hpp"

namespace frontsteal::render {

namespace {

constexpr int kGroupSize = 128;

// One work group per patch. Header of patch p: header[2p] = (degree_u, degree_v, n_u, n_v), header[2p+1] =
// (first control point, first vertex, first index, 0). ORDER (the largest degree + 1 the program handles) and the
// planted defects (tests only) are #defines put in front.
constexpr const char* kShaderBody = R"(
layout(local_size_x = 128) in;
layout(std430, binding = 0) readonly buffer Headers { uvec4 header[]; };
layout(std430, binding = 1) readonly buffer Controls { vec4 control[]; };
layout(std430, binding = 2) writeonly buffer Positions { float position[]; };
layout(std430, binding = 3) writeonly buffer Normals { float normal[]; };
layout(std430, binding = 4) writeonly buffer Uvs { float uv[]; };
layout(std430, binding = 5) writeonly buffer Indices { uint index[]; };
uniform uint patch_base;

shared vec4 hull[ORDER * ORDER];

// B_i^d(t) and B_i^d'(t), i = 0..d, by the triangle recurrence (bezier_patch.hpp's bernstein, in float).
void bernstein(uint d, float t, out float value[ORDER], out float derivative[ORDER]) {
  float b[ORDER];
  for (uint i = 0u; i < uint(ORDER); ++i) b[i] = 0.0;
  b[0] = 1.0;
  float s = 1.0 - t;
  for (uint k = 1u; k < d; ++k) {
    float carry = 0.0;
    for (uint i = 0u; i < k; ++i) {
      float keep = b[i];
      b[i] = carry + s * keep;
      carry = t * keep;
    }
    b[k] = carry;
  }
  for (uint i = 0u; i <= d; ++i) {
    float lower = i > 0u ? b[i - 1u] : 0.0;
    float same = i < d ? b[i] : 0.0;
    derivative[i] = float(d) * (lower - same);
  }
  float carry = 0.0;
  for (uint i = 0u; i < d; ++i) {
    value[i] = carry + s * b[i];
    carry = t * b[i];
  }
  value[d] = carry;
}

// Position, S_u, S_v at (u, v) from the control points in shared memory.
void surface(uint m, uint n, float u, float v, out vec3 p, out vec3 pu, out vec3 pv) {
  float bu[ORDER], du[ORDER], bv[ORDER], dv[ORDER];
  bernstein(m, u, bu, du);
  bernstein(n, v, bv, dv);
  vec4 s = vec4(0.0), su = vec4(0.0), sv = vec4(0.0);
  for (uint i = 0u; i <= m; ++i) {
    vec4 row = vec4(0.0), row_v = vec4(0.0);
    for (uint j = 0u; j <= n; ++j) {
      vec4 h = hull[i * (n + 1u) + j];
      row += bv[j] * h;
      row_v += dv[j] * h;
    }
    s += bu[i] * row;
    su += du[i] * row;
    sv += bu[i] * row_v;
  }
  p = s.xyz / s.w;
  pu = (su.xyz - p * su.w) / s.w;
  pv = (sv.xyz - p * sv.w) / s.w;
}

void main() {
  uint patch_index = patch_base + gl_WorkGroupID.x;
  uvec4 shape = header[2u * patch_index];
  uvec4 where = header[2u * patch_index + 1u];
  uint m = shape.x, n = shape.y, nu = shape.z, nv = shape.w;
  uint controls = (m + 1u) * (n + 1u);
  for (uint k = gl_LocalInvocationID.x; k < controls; k += gl_WorkGroupSize.x) hull[k] = control[where.x + k];
  barrier();
  uint row_length = nv + 1u;
  uint vertices = (nu + 1u) * row_length;
  for (uint k = gl_LocalInvocationID.x; k < vertices; k += gl_WorkGroupSize.x) {
    uint i = k / row_length, j = k - i * row_length;
#ifdef PLANT_LAST_ROW_UNWRITTEN
    if (i == nu) continue;
#endif
    float u = float(i) / float(nu), v = float(j) / float(nv);
    vec3 p, pu, pv;
#ifdef PLANT_SWAPPED_PARAMETERS
    surface(m, n, v, u, p, pu, pv);
#else
    surface(m, n, u, v, p, pu, pv);
#endif
    vec3 c = cross(pu, pv);
    float len = length(c);
    if (!(len > 0.0)) {  // a collapsed edge: the normal a little towards the patch centre, as on the CPU
      vec3 q, qu, qv;
      surface(m, n, u + (0.5 - u) * 1e-3, v + (0.5 - v) * 1e-3, q, qu, qv);
      c = cross(qu, qv);
      len = length(c);
    }
    vec3 unit = len > 0.0 ? c / len : vec3(0.0);
    uint o = where.y + k;
    position[3u * o] = p.x; position[3u * o + 1u] = p.y; position[3u * o + 2u] = p.z;
    normal[3u * o] = unit.x; normal[3u * o + 1u] = unit.y; normal[3u * o + 2u] = unit.z;
    uv[2u * o] = u; uv[2u * o + 1u] = v;
  }
  // Two triangles per cell, counter-clockwise seen from S_u × S_v (grid_indices).
  uint cells = nu * nv;
  for (uint c = gl_LocalInvocationID.x; c < cells; c += gl_WorkGroupSize.x) {
    uint i = c / nv, j = c - i * nv;
    uint a = i * row_length + j, b = a + row_length;
    uint o = where.z + 6u * c;
    index[o] = a; index[o + 1u] = b; index[o + 2u] = b + 1u;
    index[o + 3u] = a; index[o + 4u] = b + 1u; index[o + 5u] = a + 1u;
  }
}
)";

[[noreturn]] void fail(const std::string& what) { throw GraphicsError("GPU tessellation: " + what); }

unsigned compile(GpuPlantedDefect defect, int order) {
  std::string source = "#version 430 core\n#define ORDER " + std::to_string(order) + "\n";
  if (defect == GpuPlantedDefect::swapped_parameters) source += "#define PLANT_SWAPPED_PARAMETERS 1\n";
  if (defect == GpuPlantedDefect::last_row_unwritten) source += "#define PLANT_LAST_ROW_UNWRITTEN 1\n";
  source += kShaderBody;
  const unsigned shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    fail(std::string("the compute shader did not compile: ") + log);
  }
  const unsigned program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    fail(std::string("the compute program did not link: ") + log);
  }
  return program;
}

}  // namespace

std::optional<GpuPlantedDefect> gpu_planted_defect_named(std::string_view name) {
  if (name == "none") return GpuPlantedDefect::none;
  if (name == "swapped-parameters") return GpuPlantedDefect::swapped_parameters;
  if (name == "last-row-unwritten") return GpuPlantedDefect::last_row_unwritten;
  return std::nullopt;
}

double gpu_float_error_bound(const tess::BezierPatch& patch) noexcept {
  const tess::ControlNetScale net = tess::control_net_scale(patch);
  constexpr double kUnit = 1.0 / 16777216.0;  // 2^-24
  return 4.0 * (2.0 * (patch.degree_u + patch.degree_v) + 6.0) * kUnit * net.max_coordinate * net.weight_spread;
}

GpuPatchTessellator::GpuPatchTessellator(GpuPlantedDefect defect) : defect_(defect) {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 43) {
    fail("needs OpenGL 4.3 (compute shaders); the context has " + std::to_string(major) + "." + std::to_string(minor) +
         " (make it with HeadlessGL(w, h, {4, 3}))");
  }
  use_order(kCommonOrder);
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups_);
  glGenBuffers(6, buffers_);
}

void GpuPatchTessellator::use_order(int order) {
  if (order == order_) return;
  const unsigned program = compile(defect_, order);
  if (program_ != 0) glDeleteProgram(program_);
  program_ = program;
  order_ = order;
  patch_base_location_ = glGetUniformLocation(program_, "patch_base");
}

GpuPatchTessellator::~GpuPatchTessellator() {
  glDeleteBuffers(6, buffers_);
  glDeleteProgram(program_);
}

void GpuPatchTessellator::load(const std::vector<const tess::BezierPatch*>& patches,
                               const std::vector<tess::StepSizes>& steps) {
  if (patches.size() != steps.size()) throw std::invalid_argument("GPU tessellation: one step size per patch");
  std::vector<std::uint32_t> headers;
  std::vector<float> controls;
  first_vertex_.assign(patches.size(), 0);
  first_index_.assign(patches.size(), 0);
  total_vertices_ = total_indices_ = 0;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const tess::BezierPatch& p = *patches[k];
    const tess::StepSizes s = steps[k];
    if (s.n_u < 1 || s.n_v < 1) throw std::invalid_argument("GPU tessellation: steps must be at least 1");
    first_vertex_[k] = total_vertices_;
    first_index_[k] = total_indices_;
    headers.insert(headers.end(),
                   {static_cast<std::uint32_t>(p.degree_u), static_cast<std::uint32_t>(p.degree_v),
                    static_cast<std::uint32_t>(s.n_u), static_cast<std::uint32_t>(s.n_v),
                    static_cast<std::uint32_t>(controls.size() / 4), static_cast<std::uint32_t>(total_vertices_),
                    static_cast<std::uint32_t>(total_indices_), 0u});
    for (const glm::dvec4& h : p.control) {
      controls.insert(controls.end(), {static_cast<float>(h.x), static_cast<float>(h.y), static_cast<float>(h.z),
                                       static_cast<float>(h.w)});
    }
    total_vertices_ += static_cast<std::uint64_t>(s.n_u + 1) * static_cast<std::uint64_t>(s.n_v + 1);
    total_indices_ += 6 * static_cast<std::uint64_t>(s.n_u) * static_cast<std::uint64_t>(s.n_v);
  }
  steps_ = steps;
  // Per-invocation arrays and the shared control net are sized by ORDER: the common program stays small
  // (occupancy), and a batch holding a higher degree gets a program of its own.
  int order = kCommonOrder;
  for (const tess::BezierPatch* p : patches) order = std::max({order, p->degree_u + 1, p->degree_v + 1});
  use_order(order);
  GLint64 block_limit = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block_limit);
  // The shader addresses every buffer with 32-bit offsets, in floats or indices.
  const std::uint64_t largest = std::max(3 * total_vertices_, total_indices_);
  if (largest >= (1ull << 32) || 4 * largest > static_cast<std::uint64_t>(block_limit)) {
    fail("the output needs a storage buffer of " + std::to_string(4 * largest) + " bytes; this driver allows " +
         std::to_string(block_limit) + " (and offsets must stay below 2^32): fewer patches or steps");
  }
  const auto upload = [](unsigned buffer, std::size_t bytes, const void* data) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data,
                 data != nullptr ? GL_STATIC_DRAW : GL_DYNAMIC_COPY);
  };
  upload(buffers_[0], headers.size() * 4, headers.data());
  upload(buffers_[1], controls.size() * 4, controls.data());
  upload(buffers_[2], 12 * total_vertices_, nullptr);
  upload(buffers_[3], 12 * total_vertices_, nullptr);
  upload(buffers_[4], 8 * total_vertices_, nullptr);
  upload(buffers_[5], 4 * total_indices_, nullptr);
  // Zero the outputs once, so a vertex the shader leaves unwritten reads back as (0, 0, 0), not as garbage
  // that might by chance be right.
  for (int b = 2; b < 6; ++b) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[b]);
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  if (glGetError() != GL_NO_ERROR) fail("allocating the buffers failed (out of GPU memory?)");
}

std::uint64_t GpuPatchTessellator::output_bytes() const noexcept { return 32 * total_vertices_ + 4 * total_indices_; }

void GpuPatchTessellator::dispatch() {
  glUseProgram(program_);
  for (unsigned b = 0; b < 6; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers_[b]);
  const std::size_t count = steps_.size();
  for (std::size_t base = 0; base < count; base += static_cast<std::size_t>(max_groups_)) {
    const std::size_t groups = std::min(count - base, static_cast<std::size_t>(max_groups_));
    glUniform1ui(patch_base_location_, static_cast<GLuint>(base));
    glDispatchCompute(static_cast<GLuint>(groups), 1, 1);
  }
  // Whoever reads the buffers next (a draw, a read-back) sees the shader's writes.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                  GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void GpuPatchTessellator::finish() { glFinish(); }

double GpuPatchTessellator::timed_dispatch(int times) {
  GLuint query = 0;
  glGenQueries(1, &query);
  glBeginQuery(GL_TIME_ELAPSED, query);
  for (int k = 0; k < times; ++k) dispatch();
  glEndQuery(GL_TIME_ELAPSED);
  finish();
  GLuint64 nanoseconds = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &nanoseconds);
  glDeleteQueries(1, &query);
  return static_cast<double>(nanoseconds) * 1e-9;
}

void GpuPatchTessellator::read_back(std::size_t k, tess::TriangleBuffers& out) const {
  const tess::StepSizes s = steps_.at(k);
  const std::size_t vertices = static_cast<std::size_t>(s.n_u + 1) * static_cast<std::size_t>(s.n_v + 1);
  const std::size_t indices = 6 * static_cast<std::size_t>(s.n_u) * static_cast<std::size_t>(s.n_v);
  out.positions.resize(vertices);
  out.normals.resize(vertices);
  out.uvs.resize(vertices);
  out.indices.resize(indices);
  const auto copy = [](unsigned buffer, std::uint64_t offset, std::size_t bytes, void* to) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), to);
  };
  copy(buffers_[2], 12 * first_vertex_[k], 12 * vertices, out.positions.data());
  copy(buffers_[3], 12 * first_vertex_[k], 12 * vertices, out.normals.data());
  copy(buffers_[4], 8 * first_vertex_[k], 8 * vertices, out.uvs.data());
  copy(buffers_[5], 4 * first_index_[k], 4 * indices, out.indices.data());
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}

}  // namespace frontsteal::render
