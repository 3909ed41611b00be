// view_overlay.hpp — frontsteal-view's on-screen overlay (Dear ImGui): scene and renderer, mode, scheduler,
// tolerance, update rate, tessellation rate, lag, steals per tessellation frame, and the keys — folded under one
// line until K shows them, so the first thing a user sees is the scene and its figures, not a key table over
// half of it. Rates are taken over half a second or more, so the numbers do not flicker with every frame.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "render/greedy_renderer.hpp"
#include "render/live_greedy.hpp"

namespace frontsteal::render {

struct OverlayRates {
  double updates_per_s = 0, frames_per_s = 0, steals_per_frame = 0;
  void sample(int updates, const LiveCounters& counters);  // call once per update

 private:
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  int updates0_ = 0;
  std::uint64_t frames0_ = 0, steals0_ = 0;
};

struct OverlayText {
  std::string title;     // scene and surface count
  std::string renderer;  // GL_RENDERER, version
  std::string message;   // the last action
};

// Needs an ImGui frame (between ImGui::NewFrame and ImGui::Render). Returns the overlay's size in pixels.
struct OverlaySize {
  int width = 0, height = 0;
};
OverlaySize draw_overlay(const OverlayText& text, const LiveGreedy& live, const UpdateRecord& latest,
                         const OverlayRates& rates, bool keys_shown);

}  // namespace frontsteal::render
