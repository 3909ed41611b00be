// scene_generator.cpp — the procedural plant (see scene_generator.hpp).
#include "tessellate/scene_generator.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include <glm/glm.hpp>

#include "tessellate/components.hpp"
#include "tessellate/model_format.hpp"

namespace frontsteal::tess {
namespace {

constexpr double kHalfRoot2 = 0.70710678118654752440;

// A rational profile point in the (ρ, z) half-plane.
struct ProfilePoint {
  double rho, z, w;
};
using ProfileSegment = std::vector<ProfilePoint>;  // degree = size − 1

struct Frame {
  glm::dvec3 origin{0.0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  glm::dvec3 at(double rho_c, double rho_s, double height) const { return origin + rho_c * x + rho_s * y + height * z; }
};

// Frame with z along `axis`.
Frame frame_along(const glm::dvec3& origin, const glm::dvec3& axis) {
  Frame f;
  f.origin = origin;
  f.z = glm::normalize(axis);
  const glm::dvec3 helper = std::abs(f.z.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  f.x = glm::normalize(glm::cross(helper, f.z));
  f.y = glm::cross(f.z, f.x);
  return f;
}

void flip_u(Surface& s) {
  BezierPatch& p = s.patch;
  for (int i = 0; i < (p.degree_u + 1) / 2; ++i) {
    for (int j = 0; j <= p.degree_v; ++j) std::swap(p.control[p.index(i, j)], p.control[p.index(p.degree_u - i, j)]);
  }
}

// Revolves each profile segment through quarters [q0, q1) of a turn: one patch per segment and quarter, u along
// the profile (degree of the segment), v around (rational quadratic). `outside` gives, for a point, a point the
// normal must point away from; the patch is flipped when its centre normal does not.
template <class Outside>
void revolve(Model& m, const std::string& name, const std::vector<ProfileSegment>& profile, const Frame& f, int q0,
             int q1, bool solid, int component_hint, Outside outside) {
  for (std::size_t s = 0; s < profile.size(); ++s) {
    const ProfileSegment& seg = profile[s];
    for (int q = q0; q < q1; ++q) {
      const double a0 = q * 0.5 * std::numbers::pi, a1 = (q + 1) * 0.5 * std::numbers::pi;
      const glm::dvec2 arc[3] = {{std::cos(a0), std::sin(a0)},
                                 {std::cos(a0) + std::cos(a1), std::sin(a0) + std::sin(a1)},
                                 {std::cos(a1), std::sin(a1)}};
      const double arc_w[3] = {1.0, kHalfRoot2, 1.0};
      Surface surf;
      surf.name = name + "_s" + std::to_string(s) + "q" + std::to_string(q);
      surf.patch = BezierPatch(static_cast<int>(seg.size()) - 1, 2);
      surf.solid = solid;
      surf.component = component_hint;
      for (int i = 0; i < static_cast<int>(seg.size()); ++i) {
        for (int j = 0; j < 3; ++j)
          surf.patch.set(i, j, f.at(seg[i].rho * arc[j].x, seg[i].rho * arc[j].y, seg[i].z), seg[i].w * arc_w[j]);
      }
      const SurfacePoint c = evaluate(surf.patch, 0.5, 0.5);
      if (glm::dot(c.normal, c.position - outside(c.position)) < 0) flip_u(surf);
      m.surfaces.push_back(std::move(surf));
    }
  }
}

ProfileSegment line(double r0, double z0, double r1, double z1) { return {{r0, z0, 1}, {r1, z1, 1}}; }
// Quarter circle about (rc, zc) of radius r from angle a0 to a0 + 90° (in the (ρ, z) plane).
ProfileSegment quarter_arc(double rc, double zc, double r, double a0) {
  const double a1 = a0 + 0.5 * std::numbers::pi;
  return {{rc + r * std::cos(a0), zc + r * std::sin(a0), 1},
          {rc + r * (std::cos(a0) + std::cos(a1)), zc + r * (std::sin(a0) + std::sin(a1)), kHalfRoot2},
          {rc + r * std::cos(a1), zc + r * std::sin(a1), 1}};
}

// A circle of radius r about c in (u, v), clockwise (a hole), as four cubic Bézier arcs.
TrimLoop hole(glm::dvec2 c, double ru, double rv) {
  const double k = 0.5522847498307936;
  TrimLoop loop;
  for (int q = 0; q < 4; ++q) {
    // Clockwise: angles decreasing.
    const double a0 = -q * 0.5 * std::numbers::pi, a1 = -(q + 1) * 0.5 * std::numbers::pi;
    const glm::dvec2 p0 = c + glm::dvec2(ru * std::cos(a0), rv * std::sin(a0));
    const glm::dvec2 p3 = c + glm::dvec2(ru * std::cos(a1), rv * std::sin(a1));
    const glm::dvec2 t0{ru * std::sin(a0), -rv * std::cos(a0)};
    const glm::dvec2 t1{ru * std::sin(a1), -rv * std::cos(a1)};
    loop.segments.push_back({{p0, p0 + k * t0, p3 - k * t1, p3}});
  }
  loop.segments.back().control.back() = loop.segments.front().control.front();
  return loop;
}

TrimLoop polygon(const std::vector<glm::dvec2>& pts) {
  TrimLoop loop;
  for (std::size_t k = 0; k < pts.size(); ++k) loop.segments.push_back({{pts[k], pts[(k + 1) % pts.size()]}});
  return loop;
}

class PlantBuilder {
 public:
  PlantBuilder(Model& m, std::uint64_t seed) : m_(m), rng_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  // A flat plate (bilinear) of size w × h at `corner` in the xy-plane at height z, with bolt holes.
  void plate(const std::string& name, glm::dvec3 corner, double w, double h, int holes_per_side, bool chamfer) {
    Surface s;
    s.name = name;
    s.patch = BezierPatch(1, 1);
    s.patch.set(0, 0, corner);
    s.patch.set(1, 0, corner + glm::dvec3(w, 0, 0));
    s.patch.set(0, 1, corner + glm::dvec3(0, h, 0));
    s.patch.set(1, 1, corner + glm::dvec3(w, h, 0));
    if (chamfer) {
      s.loops.push_back(polygon({{0, 0}, {0.85, 0}, {1, 0.15}, {1, 1}, {0, 1}}));
    } else {
      s.loops.push_back(polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
    }
    const double r = 0.035;
    for (int k = 0; k < holes_per_side; ++k) {
      const double t = (k + 0.5) / holes_per_side;
      for (const glm::dvec2 c : {glm::dvec2{0.08, t}, glm::dvec2{0.92, 1 - t}}) {
        if (chamfer && c.x > 0.8 && c.y < 0.25) continue;
        s.loops.push_back(hole(c, r * std::min(1.0, h / w), r * std::min(1.0, w / h)));
      }
    }
    m_.surfaces.push_back(std::move(s));
  }

  void tank(const std::string& name, glm::dvec3 base, double radius, double height) {
    const Frame f = frame_along(base, {0, 0, 1});
    // Heads and wall; revolve() flips any patch whose normal points into the tank.
    const std::vector<ProfileSegment> profile{quarter_arc(0, height - radius, radius, 0.0),
                                              line(radius, height - radius, radius, radius),
                                              quarter_arc(0, radius, radius, 1.5 * std::numbers::pi)};
    const glm::dvec3 centre = base + glm::dvec3(0, 0, 0.5 * height);
    revolve(m_, name, profile, f, 0, 4, true, -1, [&](const glm::dvec3&) { return centre; });
  }

  // A straight pipe of radius r from a to b (open ends): 4 patches.
  void pipe(const std::string& name, glm::dvec3 a, glm::dvec3 b, double r) {
    const Frame f = frame_along(a, b - a);
    const double len = glm::length(b - a);
    revolve(m_, name, {line(r, len, r, 0)}, f, 0, 4, false, -1, [&](const glm::dvec3& p) {
      return a + glm::dot(p - a, f.z) * f.z;  // the axis point level with p
    });
  }

  // A 90° elbow: the tube of radius r around the arc of radius R about `centre`, from direction d0 to d1.
  void elbow(const std::string& name, glm::dvec3 centre, glm::dvec3 d0, glm::dvec3 d1, double bend, double r) {
    Frame f;
    f.origin = centre;
    f.x = glm::normalize(d0);
    f.y = glm::normalize(d1);
    f.z = glm::cross(f.x, f.y);
    std::vector<ProfileSegment> circle;
    for (int q = 0; q < 4; ++q) circle.push_back(quarter_arc(bend, 0, r, q * 0.5 * std::numbers::pi));
    revolve(m_, name, circle, f, 0, 1, false, -1, [&](const glm::dvec3& p) {
      const glm::dvec3 in_plane = p - centre - glm::dot(p - centre, f.z) * f.z;
      return centre + bend * glm::normalize(in_plane);  // the bend's centre line
    });
  }

  // A flat ring (flange) at `centre` around `axis`: 4 patches, each with two bolt holes.
  void flange(const std::string& name, glm::dvec3 centre, glm::dvec3 axis, double r_in, double r_out) {
    const Frame f = frame_along(centre, axis);
    const std::size_t first = m_.surfaces.size();
    revolve(m_, name, {line(r_in, 0, r_out, 0)}, f, 0, 4, false, -1, [&](const glm::dvec3& p) { return p - f.z; });
    for (std::size_t k = first; k < m_.surfaces.size(); ++k) {
      Surface& s = m_.surfaces[k];
      s.loops.push_back(polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
      s.loops.push_back(hole({0.5, 0.27}, 0.18, 0.1));
      s.loops.push_back(hole({0.5, 0.73}, 0.18, 0.1));
    }
  }

  // One bay at grid position (gx, gy); returns the number of surfaces it added.
  std::size_t bay(int gx, int gy, double spacing) {
    const std::size_t before = m_.surfaces.size();
    const std::string tag = "bay" + std::to_string(gx) + "_" + std::to_string(gy);
    const glm::dvec3 o{gx * spacing, gy * spacing, 0};
    const double tr = uniform(1.2, 2.0), th = uniform(4.0, 7.0);
    plate(tag + "_base", o + glm::dvec3(-0.3 * spacing, -0.3 * spacing, 0), 0.6 * spacing, 0.6 * spacing, integer(2, 4),
          integer(0, 1) == 1);
    tank(tag + "_tank", o + glm::dvec3(0, 0, 0.05), tr, th);
    // Pipe run: out of the tank's side, an elbow up, a riser, a flange on top.
    const double pr = uniform(0.15, 0.3), bend = 2.5 * pr;
    const double z = uniform(1.0, th - 1.5);
    const glm::dvec3 start = o + glm::dvec3(tr * 0.999, 0, z);
    const glm::dvec3 knee = o + glm::dvec3(tr + uniform(1.0, 2.5), 0, z);
    pipe(tag + "_pipe", start, knee, pr);
    elbow(tag + "_elbow", knee + glm::dvec3(0, 0, bend), {0, 0, -1}, {1, 0, 0}, bend, pr);
    const glm::dvec3 riser0 = knee + glm::dvec3(bend, 0, bend);
    const glm::dvec3 riser1 = riser0 + glm::dvec3(0, 0, uniform(1.5, 4.0));
    pipe(tag + "_riser", riser0, riser1, pr);
    flange(tag + "_flange", riser1, {0, 0, 1}, pr, 2.2 * pr);
    return m_.surfaces.size() - before;
  }

 private:
  Model& m_;
  std::mt19937_64 rng_;
};

}  // namespace

Model generate_plant(const SceneOptions& options) {
  if (options.surfaces < 1) throw std::invalid_argument("a generated plant needs at least 1 surface");
  Model m;
  m.name = "plant_" + std::to_string(options.surfaces) + "_seed" + std::to_string(options.seed);
  m.surfaces.reserve(static_cast<std::size_t>(options.surfaces) + 64);
  PlantBuilder b(m, options.seed);
  const std::size_t target = static_cast<std::size_t>(options.surfaces);
  constexpr std::size_t kLargestBay = 1 + 12 + 4 + 4 + 4 + 4;
  constexpr double kSpacing = 14.0;
  const int side = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(target) / kLargestBay))));
  int placed = 0;
  while (m.surfaces.size() + kLargestBay <= target) {
    b.bay(placed % side, placed / side, kSpacing);
    ++placed;
  }
  // Fill up with bolted floor plates along a walkway south of the bays.
  for (int k = 0; m.surfaces.size() < target; ++k) {
    const glm::dvec3 corner{(k % (4 * side)) * 3.5 - 0.5 * kSpacing, -0.6 * kSpacing - (k / (4 * side)) * 3.5, 0.0};
    b.plate("walkway_" + std::to_string(k), corner, 3.4, 3.4, b.integer(1, 3), k % 5 == 0);
  }
  assign_components(m, 1e-6);
  return m;
}

Model load_scene(const std::string& spec, const std::string& data_dir) {
  if (spec == "teapot" || spec == "teacup" || spec == "teaspoon")
    return load_model(data_dir + "/models/" + spec + ".fsm");
  if (spec.rfind("plant:", 0) == 0) {
    SceneOptions o;
    const std::string rest = spec.substr(6);
    const std::size_t colon = rest.find(':');
    try {
      std::size_t used = 0;
      const std::string count = rest.substr(0, colon);
      o.surfaces = std::stoi(count, &used);
      if (used != count.size()) throw std::invalid_argument(count);
      if (colon != std::string::npos) {
        const std::string seed = rest.substr(colon + 1);
        o.seed = std::stoull(seed, &used);
        if (used != seed.size()) throw std::invalid_argument(seed);
      }
    } catch (const std::logic_error&) {
      throw std::invalid_argument("scene '" + spec +
                                  "': expected plant:<surfaces>[:<seed>], e.g. plant:5302 or plant:15906:7");
    }
    if (o.surfaces < 1) throw std::invalid_argument("scene '" + spec + "': the surface count must be at least 1");
    return generate_plant(o);
  }
  Model m = load_model(spec);
  bool any_missing = false;
  for (const Surface& s : m.surfaces) any_missing |= s.component < 0;
  if (any_missing) assign_components(m, 1e-6);
  return m;
}

}  // namespace frontsteal::tess
