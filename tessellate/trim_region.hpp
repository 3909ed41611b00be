// trim_region.hpp — a trimmed region cut along the lines of a rectilinear grid, cell by cell.
//
// Input: closed trim polylines in (u, v) with the material on their left (outer boundaries counter-clockwise,
// holes clockwise) that do not cross each other, and a grid given by its lines u_0 < … < u_nu, v_0 < … < v_nv.
// Output, per cell: empty, full, or partial with its pieces (an outer ring and its holes). The tessellator uses
// it on the uniform n_u × n_v grid of a patch (trimmed cells are then triangulated); the CAD importer uses it on
// the knot grid of a B-spline face to give each Bézier patch its own trim loops. The algorithm is the one of
// Kumar & Manocha (CAD 27(7), 1995) in outline:
//   1. Points lying on a grid line are moved off it by a tiny amount (10⁻⁶ of a cell, towards the domain's
//      inside on its boundary). No trim vertex is then on a line, so every crossing is transversal; a segment
//      through a grid corner is recognized (equal crossing parameters) and passes diagonally.
//   2. Each loop is walked segment by segment; crossings with grid lines are inserted exactly on the line and
//      split the loop into chains, one per visit of a cell. A chain enters the cell at a boundary position s and
//      leaves it at s', measured counter-clockwise along the cell's perimeter (bottom edge [0,1), right [1,2),
//      top [2,3), left [3,4)). A loop that never crosses a line is a closed chain inside one cell.
//   3. Cells without chains are classified by a scanline per row (winding number of the trim loops at the
//      cell's left edge, at mid-height): inside → full, outside → empty. This is the "inside/outside propagated
//      across cells" step, done as a sweep.
//   4. A partial cell's pieces are traced: leave a chain at its exit s', walk counter-clockwise along the cell
//      boundary (adding the corners passed) to the next chain's entry, follow it, until the ring closes. Since
//      material is on the left of every chain, the walk along the boundary runs through material. Closed chains
//      become new pieces (counter-clockwise) or holes of the piece containing them (clockwise); a cell with only
//      closed chains starts from its full square when its boundary is inside.
// Inconsistent input (crossing loops, wrong orientation) cannot always be detected up front; tracing then finds
// a chain used twice or a hole in no piece, drops what it cannot place and counts it in `inconsistencies()`.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/polygon_triangulation.hpp"

namespace frontsteal::tess {

using Polygon2 = std::vector<glm::dvec2>;  // closed: the last point is not repeated

enum class CellKind : std::uint8_t { empty, full, partial };

struct TracedPiece {
  PolygonRing outer;               // counter-clockwise
  std::vector<PolygonRing> holes;  // clockwise
};

class GridTrimmer {
 public:
  // Vertex ids in traced rings: a trim point (index into points()), or a grid corner with this bit set and
  // the corner's index iu·(nv+1) + iv below it.
  static constexpr std::uint32_t kCornerBit = 0x8000'0000u;

  // Cuts `loops` along the grid. The spans must stay valid until the next run().
  void run(std::span<const Polygon2> loops, std::span<const double> u_lines, std::span<const double> v_lines) {
    u_ = u_lines;
    v_ = v_lines;
    nu_ = static_cast<int>(u_.size()) - 1;
    nv_ = static_cast<int>(v_.size()) - 1;
    inconsistencies_ = 0;
    base_winding_ = 0;
    points_.clear();
    chains_.clear();
    chain_points_.clear();
    loop_ranges_.clear();
    kind_.assign(static_cast<std::size_t>(nu_ * nv_), CellKind::empty);
    has_chains_.assign(static_cast<std::size_t>(nu_ * nv_), 0);
    for (const Polygon2& loop : loops) add_loop(loop);
    for (const Chain& c : chains_) has_chains_[static_cast<std::size_t>(c.cell)] = 1;
    classify_by_scanlines();
    index_chains_by_cell();
  }

  int cells_u() const noexcept { return nu_; }
  int cells_v() const noexcept { return nv_; }
  CellKind kind(int iu, int iv) const noexcept { return kind_[static_cast<std::size_t>(iu * nv_ + iv)]; }
  const std::vector<glm::dvec2>& points() const noexcept { return points_; }
  int inconsistencies() const noexcept { return inconsistencies_; }
  glm::dvec2 corner(std::uint32_t id) const noexcept {
    const std::uint32_t k = id & ~kCornerBit;
    return {u_[k / static_cast<std::uint32_t>(nv_ + 1)], v_[k % static_cast<std::uint32_t>(nv_ + 1)]};
  }
  glm::dvec2 position(std::uint32_t id) const noexcept { return (id & kCornerBit) ? corner(id) : points_[id]; }

  // The pieces of a partial cell (valid until the next call).
  std::span<const TracedPiece> trace(int iu, int iv) {
    pieces_used_ = 0;
    const int cell = iu * nv_ + iv;
    const std::uint32_t begin = cell_chain_begin_[static_cast<std::size_t>(cell)];
    const std::uint32_t end = cell_chain_begin_[static_cast<std::size_t>(cell) + 1];
    open_.clear();
    closed_.clear();
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t c = chain_order_[k];
      (chains_[c].s_in < 0 ? closed_ : open_).push_back(c);
    }
    used_.assign(open_.size(), 0);
    for (std::size_t start = 0; start < open_.size(); ++start) {
      if (used_[start]) continue;
      TracedPiece& piece = new_piece();
      std::size_t c = start;
      bool ok = true;
      for (std::size_t guard = 0; guard <= open_.size(); ++guard) {
        const Chain& ch = chains_[open_[c]];
        for (std::uint32_t p = ch.first; p < ch.first + ch.count; ++p) push_vertex(piece.outer, chain_points_[p]);
        used_[c] = 1;
        // Next entry counter-clockwise from this exit.
        std::size_t next = c;
        double best = 5.0;
        for (std::size_t k = 0; k < open_.size(); ++k) {
          const double d = std::fmod(chains_[open_[k]].s_in - ch.s_out + 8.0, 4.0);
          if (d < best) best = d, next = k;
        }
        add_corners_between(piece.outer, iu, iv, ch.s_out, best);
        if (next == start) break;
        if (used_[next]) {
          ok = false;
          break;
        }
        c = next;
      }
      if (!ok || piece.outer.size() < 3) {
        ++inconsistencies_;
        --pieces_used_;
      }
    }
    if (open_.empty() && base_inside_[static_cast<std::size_t>(cell)]) {
      TracedPiece& piece = new_piece();
      for (int k = 0; k < 4; ++k) piece.outer.push_back(corner_vertex(iu, iv, k));
    }
    // Closed chains: islands become pieces first, then holes find their piece.
    for (int pass = 0; pass < 2; ++pass) {
      for (std::uint32_t c : closed_) {
        const Chain& ch = chains_[c];
        const bool ccw = ring_area2(ch) > 0;
        if (pass == 0 && ccw) {
          TracedPiece& piece = new_piece();
          for (std::uint32_t p = ch.first; p < ch.first + ch.count; ++p) push_vertex(piece.outer, chain_points_[p]);
        } else if (pass == 1 && !ccw) {
          const glm::dvec2 probe = points_[chain_points_[ch.first]];
          TracedPiece* home = nullptr;
          for (std::size_t k = 0; k < pieces_used_ && !home; ++k) {
            if (inside_ring(pieces_[k].outer, probe)) home = &pieces_[k];
          }
          if (!home) {
            ++inconsistencies_;
            continue;
          }
          PolygonRing& hole = new_hole(*home);
          for (std::uint32_t p = ch.first; p < ch.first + ch.count; ++p) push_vertex(hole, chain_points_[p]);
        }
      }
    }
    return {pieces_.data(), pieces_used_};
  }

 private:
  struct Chain {
    int cell;
    double s_in;                 // perimeter position of the entry; −1 for a closed chain
    double s_out;                // perimeter position of the exit
    std::uint32_t first, count;  // into chain_points_
  };
  struct Event {
    std::uint32_t point;
    int cell_after;  // −1 for an ordinary vertex; the new cell for a crossing
    double s_out, s_in;
  };

  static double nudge(double x, std::span<const double> lines) {
    const double lo = lines.front(), hi = lines.back();
    x = std::clamp(x, lo, hi);
    const double tol = 1e-9 * (hi - lo);
    const auto it = std::lower_bound(lines.begin(), lines.end(), x);
    for (auto k = it == lines.begin() ? it : it - 1; k != lines.end() && k <= it; ++k) {
      if (std::abs(x - *k) > tol) continue;
      if (k + 1 == lines.end()) return *k - 1e-6 * (*k - *(k - 1));
      return *k + 1e-6 * (*(k + 1) - *k);
    }
    return x;
  }

  int cell_of(double x, std::span<const double> lines) const {
    const auto it = std::upper_bound(lines.begin(), lines.end(), x);
    return std::clamp(static_cast<int>(it - lines.begin()) - 1, 0, static_cast<int>(lines.size()) - 2);
  }

  // A counter-clockwise loop running along the domain's boundary bounds nothing the domain does not: it is
  // kept out of the walk (its points would all be nudged into slivers) and counted as winding +1 everywhere.
  bool is_domain_boundary(const Polygon2& loop) const {
    const double u0 = u_.front(), u1 = u_.back(), v0 = v_.front(), v1 = v_.back();
    const double tol = 1e-9 * std::max(u1 - u0, v1 - v0);
    for (const glm::dvec2& p : loop) {
      const bool on = std::abs(p.x - u0) <= tol || std::abs(p.x - u1) <= tol || std::abs(p.y - v0) <= tol ||
                      std::abs(p.y - v1) <= tol;
      if (!on) return false;
    }
    double area2 = 0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const glm::dvec2& p = loop[k];
      const glm::dvec2& q = loop[(k + 1) % loop.size()];
      area2 += p.x * q.y - q.x * p.y;
    }
    return std::abs(0.5 * area2 - (u1 - u0) * (v1 - v0)) <= 1e-9 * (u1 - u0) * (v1 - v0);
  }

  void add_loop(const Polygon2& loop) {
    if (is_domain_boundary(loop)) {
      ++base_winding_;
      return;
    }
    const std::uint32_t start = static_cast<std::uint32_t>(points_.size());
    for (const glm::dvec2& raw : loop) {
      const glm::dvec2 p{nudge(raw.x, u_), nudge(raw.y, v_)};
      if (points_.size() > start && points_.back() == p) continue;
      points_.push_back(p);
    }
    while (points_.size() > start + 1 && points_.back() == points_[start]) points_.pop_back();
    const std::uint32_t n = static_cast<std::uint32_t>(points_.size()) - start;
    if (n < 3) {
      points_.resize(start);
      return;
    }
    loop_ranges_.push_back({start, n});
    // Walk the loop, recording vertices and crossings as events.
    events_.clear();
    int iu = cell_of(points_[start].x, u_), iv = cell_of(points_[start].y, v_);
    const int first_cell = iu * nv_ + iv;
    for (std::uint32_t k = 0; k < n; ++k) {
      const glm::dvec2 p = points_[start + k];
      const glm::dvec2 q = points_[start + (k + 1) % n];
      events_.push_back({start + k, -1, 0, 0});
      walk_segment(p, q, iu, iv);
    }
    // No crossing: one closed chain.
    const auto first_crossing =
        std::find_if(events_.begin(), events_.end(), [](const Event& e) { return e.cell_after >= 0; });
    if (first_crossing == events_.end()) {
      const std::uint32_t first = static_cast<std::uint32_t>(chain_points_.size());
      for (const Event& e : events_) chain_points_.push_back(e.point);
      chains_.push_back({first_cell, -1.0, -1.0, first, n});
      return;
    }
    // Rotate to begin at the first crossing; every crossing ends one chain and starts the next.
    const std::size_t r = static_cast<std::size_t>(first_crossing - events_.begin());
    const std::size_t m = events_.size();
    Chain current{first_crossing->cell_after, first_crossing->s_in, 0, static_cast<std::uint32_t>(chain_points_.size()),
                  0};
    chain_points_.push_back(first_crossing->point);
    for (std::size_t step = 1; step <= m; ++step) {
      const Event& e = events_[(r + step) % m];
      chain_points_.push_back(e.point);
      if (e.cell_after >= 0) {
        current.s_out = e.s_out;
        current.count = static_cast<std::uint32_t>(chain_points_.size()) - current.first;
        if (!degenerate(current)) chains_.push_back(current);  // a touch at a corner, rounded: no chain
        if (step == m) break;
        current = {e.cell_after, e.s_in, 0, static_cast<std::uint32_t>(chain_points_.size()), 0};
        chain_points_.push_back(e.point);
      }
    }
  }

  bool degenerate(const Chain& c) const {
    for (std::uint32_t k = 1; k < c.count; ++k) {
      if (points_[chain_points_[c.first + k]] != points_[chain_points_[c.first]]) return false;
    }
    return true;
  }

  // Crossings of segment p→q with the grid lines, in order, as events; updates the current cell (iu, iv).
  void walk_segment(const glm::dvec2& p, const glm::dvec2& q, int& iu, int& iv) {
    const int du = q.x > p.x ? 1 : -1;
    const int dv = q.y > p.y ? 1 : -1;
    const int target_u = cell_of(q.x, u_), target_v = cell_of(q.y, v_);
    while (iu != target_u || iv != target_v) {
      // Next vertical line in the direction of travel, and the next horizontal one.
      double tu = 2.0, tv = 2.0;
      if (iu != target_u) tu = (u_[static_cast<std::size_t>(du > 0 ? iu + 1 : iu)] - p.x) / (q.x - p.x);
      if (iv != target_v) tv = (v_[static_cast<std::size_t>(dv > 0 ? iv + 1 : iv)] - p.y) / (q.y - p.y);
      const double u0 = u_[static_cast<std::size_t>(iu)], u1 = u_[static_cast<std::size_t>(iu) + 1];
      const double v0 = v_[static_cast<std::size_t>(iv)], v1 = v_[static_cast<std::size_t>(iv) + 1];
      Event e{static_cast<std::uint32_t>(points_.size()), 0, 0, 0};
      if (std::abs(tu - tv) <= 1e-12) {  // through a grid corner: pass diagonally
        const glm::dvec2 x{du > 0 ? u1 : u0, dv > 0 ? v1 : v0};
        points_.push_back(x);
        e.s_out = du > 0 ? (dv > 0 ? 2.0 : 1.0) : (dv > 0 ? 3.0 : 0.0);
        e.s_in = du > 0 ? (dv > 0 ? 0.0 : 3.0) : (dv > 0 ? 1.0 : 2.0);
        iu += du;
        iv += dv;
      } else if (tu < tv) {  // through a vertical line
        const double y = std::clamp(p.y + tu * (q.y - p.y), v0, v1);
        points_.push_back({du > 0 ? u1 : u0, y});
        const double f = (y - v0) / (v1 - v0);
        e.s_out = du > 0 ? 1.0 + f : 4.0 - f;
        e.s_in = du > 0 ? 4.0 - f : 1.0 + f;
        iu += du;
      } else {  // through a horizontal line
        const double x = std::clamp(p.x + tv * (q.x - p.x), u0, u1);
        points_.push_back({x, dv > 0 ? v1 : v0});
        const double f = (x - u0) / (u1 - u0);
        e.s_out = dv > 0 ? 3.0 - f : f;
        e.s_in = dv > 0 ? f : 3.0 - f;
        iv += dv;
      }
      e.s_out = std::fmod(e.s_out, 4.0);
      e.s_in = std::fmod(e.s_in, 4.0);
      e.cell_after = iu * nv_ + iv;
      events_.push_back(e);
    }
  }

  // Step 3: winding number at each row's mid-height, at every cell's left edge.
  void classify_by_scanlines() {
    base_inside_.assign(static_cast<std::size_t>(nu_ * nv_), 0);
    // Each edge's crossings go to the scanlines it spans (a bucket per row, by two passes: count, then fill), so
    // the work is the crossings, not rows × edges. An edge crosses y when min(a.y, b.y) ≤ y < max(a.y, b.y).
    scanline_y_.resize(static_cast<std::size_t>(nv_));
    for (int iv = 0; iv < nv_; ++iv) {
      scanline_y_[static_cast<std::size_t>(iv)] =
          0.5 * (v_[static_cast<std::size_t>(iv)] + v_[static_cast<std::size_t>(iv) + 1]);
    }
    const auto rows_spanned = [this](const glm::dvec2& a, const glm::dvec2& b) {
      const auto first = std::lower_bound(scanline_y_.begin(), scanline_y_.end(), std::min(a.y, b.y));
      const auto last = std::lower_bound(first, scanline_y_.end(), std::max(a.y, b.y));
      return std::pair(static_cast<std::size_t>(first - scanline_y_.begin()),
                       static_cast<std::size_t>(last - scanline_y_.begin()));
    };
    const auto for_each_edge = [this](auto&& f) {
      for (const auto& [start, n] : loop_ranges_) {
        for (std::uint32_t k = 0; k < n; ++k) f(points_[start + k], points_[start + (k + 1 == n ? 0 : k + 1)]);
      }
    };
    scanline_begin_.assign(static_cast<std::size_t>(nv_) + 1, 0);
    for_each_edge([&](const glm::dvec2& a, const glm::dvec2& b) {
      const auto [first, last] = rows_spanned(a, b);
      for (std::size_t r = first; r < last; ++r) ++scanline_begin_[r + 1];
    });
    for (std::size_t r = 0; r < static_cast<std::size_t>(nv_); ++r) scanline_begin_[r + 1] += scanline_begin_[r];
    crossings_.resize(scanline_begin_.back());
    scanline_fill_.assign(scanline_begin_.begin(), scanline_begin_.end() - 1);
    for_each_edge([&](const glm::dvec2& a, const glm::dvec2& b) {
      const auto [first, last] = rows_spanned(a, b);
      for (std::size_t r = first; r < last; ++r) {
        const double y = scanline_y_[r];
        const double x = a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
        crossings_[scanline_fill_[r]++] = {x, b.y > a.y ? 1 : -1};
      }
    });
    for (int iv = 0; iv < nv_; ++iv) {
      const auto row_begin = crossings_.begin() + scanline_begin_[static_cast<std::size_t>(iv)];
      const auto row_end = crossings_.begin() + scanline_begin_[static_cast<std::size_t>(iv) + 1];
      std::sort(row_begin, row_end, [](const auto& l, const auto& r) { return l.first < r.first; });
      // Sweep from the right: winding(x) = Σ directions of crossings right of x.
      int winding = base_winding_;
      auto k = row_end;
      for (int iu = nu_ - 1; iu >= 0; --iu) {
        const double x = u_[static_cast<std::size_t>(iu)];
        while (k != row_begin && (k - 1)->first > x) winding += (--k)->second;
        const std::size_t cell = static_cast<std::size_t>(iu * nv_ + iv);
        base_inside_[cell] = winding > 0;
        kind_[cell] = has_chains_[cell] ? CellKind::partial : (winding > 0 ? CellKind::full : CellKind::empty);
      }
    }
  }

  void index_chains_by_cell() {
    cell_chain_begin_.assign(static_cast<std::size_t>(nu_ * nv_) + 1, 0);
    for (const Chain& c : chains_) ++cell_chain_begin_[static_cast<std::size_t>(c.cell) + 1];
    for (std::size_t k = 1; k < cell_chain_begin_.size(); ++k) cell_chain_begin_[k] += cell_chain_begin_[k - 1];
    chain_order_.resize(chains_.size());
    fill_.assign(cell_chain_begin_.begin(), cell_chain_begin_.end() - 1);
    for (std::uint32_t c = 0; c < chains_.size(); ++c)
      chain_order_[fill_[static_cast<std::size_t>(chains_[c].cell)]++] = c;
  }

  TracedPiece& new_piece() {
    if (pieces_used_ == pieces_.size()) pieces_.emplace_back();
    TracedPiece& p = pieces_[pieces_used_++];
    p.outer.clear();
    // The hole rings go back to a pool with their capacity, so the next hole reuses one instead of allocating.
    for (PolygonRing& hole : p.holes) spare_rings_.push_back(std::move(hole));
    p.holes.clear();
    return p;
  }
  PolygonRing& new_hole(TracedPiece& piece) {
    if (spare_rings_.empty()) return piece.holes.emplace_back();
    PolygonRing& ring = piece.holes.emplace_back(std::move(spare_rings_.back()));
    spare_rings_.pop_back();
    ring.clear();
    return ring;
  }

  void push_vertex(PolygonRing& ring, std::uint32_t id) const {
    const glm::dvec2 uv = position(id);
    if (!ring.empty() && ring.back().uv == uv) return;
    ring.push_back({uv, id});
  }

  // Corner k of cell (iu, iv): 0 bottom-left, 1 bottom-right, 2 top-right, 3 top-left (perimeter order).
  PolygonVertex corner_vertex(int iu, int iv, int k) const {
    const int cu = iu + (k == 1 || k == 2 ? 1 : 0);
    const int cv = iv + (k >= 2 ? 1 : 0);
    const std::uint32_t id = kCornerBit | static_cast<std::uint32_t>(cu * (nv_ + 1) + cv);
    return {corner(id), id};
  }

  // Corners strictly between perimeter position s and s + distance (counter-clockwise).
  void add_corners_between(PolygonRing& ring, int iu, int iv, double s, double distance) const {
    double first = std::floor(s) + 1.0;
    for (double c = first; c - s < distance; c += 1.0) {
      if (c - s <= 0) continue;
      push_vertex(ring, corner_vertex(iu, iv, static_cast<int>(c) % 4).id);
    }
  }

  double ring_area2(const Chain& ch) const {
    double a = 0;
    for (std::uint32_t k = 0; k < ch.count; ++k) {
      const glm::dvec2& p = points_[chain_points_[ch.first + k]];
      const glm::dvec2& q = points_[chain_points_[ch.first + (k + 1) % ch.count]];
      a += p.x * q.y - q.x * p.y;
    }
    return a;
  }

  static bool inside_ring(const PolygonRing& ring, const glm::dvec2& p) {
    bool in = false;
    for (std::size_t k = 0, j = ring.size() - 1; k < ring.size(); j = k++) {
      const glm::dvec2& a = ring[k].uv;
      const glm::dvec2& b = ring[j].uv;
      if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
    }
    return in;
  }

  std::span<const double> u_, v_;
  int nu_ = 0, nv_ = 0;
  int inconsistencies_ = 0;
  int base_winding_ = 0;
  std::vector<glm::dvec2> points_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> loop_ranges_;
  std::vector<Event> events_;
  std::vector<Chain> chains_;
  std::vector<std::uint32_t> chain_points_;
  std::vector<CellKind> kind_;
  std::vector<std::uint8_t> has_chains_, base_inside_;
  std::vector<std::pair<double, int>> crossings_;  // classify_by_scanlines: (x, direction), row by row
  std::vector<double> scanline_y_;
  std::vector<std::size_t> scanline_begin_, scanline_fill_;
  std::vector<std::uint32_t> cell_chain_begin_, chain_order_, fill_;
  std::vector<std::uint32_t> open_, closed_;
  std::vector<std::uint8_t> used_;
  std::vector<TracedPiece> pieces_;
  std::vector<PolygonRing> spare_rings_;  // hole rings of earlier pieces, kept for their capacity
  std::size_t pieces_used_ = 0;
};

// The importer's view: every cell's cover, in plain coordinates.
struct RegionPiece {
  Polygon2 outer;               // counter-clockwise
  std::vector<Polygon2> holes;  // clockwise
};
struct CellCover {
  enum class Kind { empty, full, partial } kind = Kind::empty;
  std::vector<RegionPiece> pieces;  // partial cells only
};

// The region bounded by `loops`, split along the grid; (u_lines.size()−1)·(v_lines.size()−1) covers, index
// iu·(v_lines.size()−1) + iv. Lines must be strictly increasing; first and last are the domain's bounds.
inline std::vector<CellCover> split_region(const std::vector<Polygon2>& loops, const std::vector<double>& u_lines,
                                           const std::vector<double>& v_lines) {
  GridTrimmer trimmer;
  trimmer.run(loops, u_lines, v_lines);
  std::vector<CellCover> out(static_cast<std::size_t>(trimmer.cells_u() * trimmer.cells_v()));
  const auto plain = [](const PolygonRing& ring) {
    Polygon2 p;
    for (const PolygonVertex& v : ring) p.push_back(v.uv);
    return p;
  };
  for (int iu = 0; iu < trimmer.cells_u(); ++iu) {
    for (int iv = 0; iv < trimmer.cells_v(); ++iv) {
      CellCover& cover = out[static_cast<std::size_t>(iu * trimmer.cells_v() + iv)];
      switch (trimmer.kind(iu, iv)) {
        case CellKind::empty: cover.kind = CellCover::Kind::empty; break;
        case CellKind::full: cover.kind = CellCover::Kind::full; break;
        case CellKind::partial:
          cover.kind = CellCover::Kind::partial;
          for (const TracedPiece& piece : trimmer.trace(iu, iv)) {
            RegionPiece r{plain(piece.outer), {}};
            for (const PolygonRing& h : piece.holes) r.holes.push_back(plain(h));
            cover.pieces.push_back(std::move(r));
          }
          if (cover.pieces.empty()) cover.kind = CellCover::Kind::empty;
          break;
      }
    }
  }
  return out;
}

}  // namespace frontsteal::tess
