// cost_trace.cpp — the trace's text format (cost_trace.hpp).
#include "papers/cost_trace.hpp"

#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace frontsteal::papers {

double CostTrace::frame_cost_ns(std::size_t f) const {
  return std::accumulate(cost_ns.at(f).begin(), cost_ns.at(f).end(), 0.0);
}

double CostTrace::path_cost_ns() const {
  double total = 0;
  for (std::size_t f = 0; f < frames(); ++f) total += frame_cost_ns(f);
  return total;
}

void write_cost_trace(const CostTrace& t, const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) throw TraceError("cannot write trace " + file.string());
  out << "frontsteal-cost-trace 1\n"
      << "scene " << t.scene << "\npath " << t.path << "\nsurfaces " << t.surfaces() << "\nframes " << t.frames()
      << "\nwidth " << t.width << "\nheight " << t.height << "\ntolerance_px " << t.tolerance_px << "\npasses "
      << t.passes << "\nmachine " << t.machine << "\ncommit " << t.commit << '\n';
  out << std::setprecision(9);
  for (std::size_t s = 0; s < t.surfaces(); ++s) {
    out << "surface " << s << ' ' << t.centres[s][0] << ' ' << t.centres[s][1] << ' ' << t.centres[s][2] << ' '
        << t.estimates[s] << '\n';
  }
  out << std::fixed << std::setprecision(0);
  for (std::size_t f = 0; f < t.frames(); ++f) {
    out << "frame " << f;
    for (double c : t.cost_ns[f]) out << ' ' << c;
    out << '\n';
  }
  if (!out) throw TraceError("error while writing trace " + file.string());
}

CostTrace read_cost_trace(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw TraceError("cannot open trace " + file.string());
  CostTrace t;
  std::string line;
  std::size_t line_no = 0;
  auto fail = [&](const std::string& why) -> TraceError {
    return TraceError(file.string() + ":" + std::to_string(line_no) + ": " + why);
  };
  std::size_t surfaces = 0, frames = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    std::istringstream s(line);
    std::string key;
    s >> key;
    if (!header) {
      int version = 0;
      if (key != "frontsteal-cost-trace" || !(s >> version) || version != 1) {
        throw fail("not a frontsteal cost trace (expected 'frontsteal-cost-trace 1')");
      }
      header = true;
      continue;
    }
    auto rest = [&] {
      std::string r;
      std::getline(s >> std::ws, r);
      return r;
    };
    if (key == "scene")
      t.scene = rest();
    else if (key == "path")
      t.path = rest();
    else if (key == "machine")
      t.machine = rest();
    else if (key == "commit")
      t.commit = rest();
    else if (key == "surfaces") {
      if (!(s >> surfaces) || surfaces == 0) throw fail("bad surface count");
    } else if (key == "frames") {
      if (!(s >> frames) || frames == 0) throw fail("bad frame count");
    } else if (key == "width") {
      if (!(s >> t.width)) throw fail("bad width");
    } else if (key == "height") {
      if (!(s >> t.height)) throw fail("bad height");
    } else if (key == "tolerance_px") {
      if (!(s >> t.tolerance_px)) throw fail("bad tolerance");
    } else if (key == "passes") {
      if (!(s >> t.passes)) throw fail("bad pass count");
    } else if (key == "surface") {
      std::size_t id = 0;
      std::array<double, 3> c{};
      double e = 0;
      if (!(s >> id >> c[0] >> c[1] >> c[2] >> e)) throw fail("bad surface line");
      if (id != t.centres.size()) throw fail("surface " + std::to_string(id) + " out of order");
      t.centres.push_back(c);
      t.estimates.push_back(e);
    } else if (key == "frame") {
      std::size_t f = 0;
      if (!(s >> f) || f != t.cost_ns.size()) throw fail("frame out of order");
      std::vector<double> costs;
      costs.reserve(surfaces);
      double c = 0;
      while (s >> c) {
        if (c < 0) throw fail("negative cost");
        costs.push_back(c);
      }
      if (!s.eof()) throw fail("bad cost value");
      if (costs.size() != surfaces) {
        throw fail("frame " + std::to_string(f) + " has " + std::to_string(costs.size()) + " costs, expected " +
                   std::to_string(surfaces));
      }
      t.cost_ns.push_back(std::move(costs));
    } else {
      throw fail("unknown key '" + key + "'");
    }
  }
  if (!header) throw TraceError(file.string() + ": empty file, not a frontsteal cost trace");
  if (t.centres.size() != surfaces) throw TraceError(file.string() + ": surface lines do not match 'surfaces'");
  if (t.cost_ns.size() != frames) {
    throw TraceError(file.string() + ": " + std::to_string(t.cost_ns.size()) + " frame lines, header says " +
                     std::to_string(frames) + " (truncated file?)");
  }
  return t;
}

}  // namespace frontsteal::papers
