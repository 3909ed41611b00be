// view_overlay.cpp — frontsteal-view's overlay (view_overlay.hpp).
#include "render/view_overlay.hpp"

#include <imgui.h>

#include "render/view_controls.hpp"

namespace frontsteal::render {

void OverlayRates::sample(int updates, const LiveCounters& c) {
  const auto now = std::chrono::steady_clock::now();
  const double dt = std::chrono::duration<double>(now - t0_).count();
  if (dt < 0.5) return;
  updates_per_s = (updates - updates0_) / dt;
  frames_per_s = static_cast<double>(c.tessellation_frames - frames0_) / dt;
  if (c.tessellation_frames > frames0_) {  // else keep the last value: no frame, no new steal count
    steals_per_frame = static_cast<double>(c.steals - steals0_) / static_cast<double>(c.tessellation_frames - frames0_);
  }
  t0_ = now;
  updates0_ = updates;
  frames0_ = c.tessellation_frames;
  steals0_ = c.steals;
}

OverlaySize draw_overlay(const OverlayText& text, const LiveGreedy& live, const UpdateRecord& rec,
                         const OverlayRates& rates, bool keys_shown) {
  const LiveCounters c = live.counters();
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.7f);
  ImGui::Begin("frontsteal-view", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  ImGui::TextUnformatted(text.title.c_str());
  ImGui::TextUnformatted(text.renderer.c_str());
  ImGui::Separator();
  ImGui::Text("mode        %s", live.synchronized() ? "synchronized (pusher waits)" : "lagging (pusher never waits)");
  ImGui::Text("scheduler   %s, %u tessellator(s)", live.scheduler().c_str(), live.tessellators());
  ImGui::Text("tolerance   %.3g px", live.tolerance());
  ImGui::Text("updates     %.1f /s   (draw %.2f ms, %llu triangles)", rates.updates_per_s, rec.draw_ms,
              static_cast<unsigned long long>(rec.triangles));
  ImGui::Text("tessellation %.1f frames/s   (last %.1f ms%s)", rates.frames_per_s, c.last_frame_ms,
              rates.frames_per_s == 0 && rec.max_lag == 0 ? ", idle: the view is unchanged" : "");
  ImGui::Text("remade      %llu surfaces last frame (the rest reused)",
              static_cast<unsigned long long>(c.last_frame_remade));
  ImGui::Text("lag         mean %.2f, max %d updates", rec.mean_lag, rec.max_lag);
  ImGui::Text("steals      %.1f per frame (last frame %llu)", rates.steals_per_frame,
              static_cast<unsigned long long>(c.last_frame_steals));
  if (c.inconsistencies > 0) {
    ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "AUDIT: %llu failing surface tessellations",
                       static_cast<unsigned long long>(c.inconsistencies));
  }
  if (!text.message.empty()) ImGui::Text("> %s", text.message.c_str());
  ImGui::Separator();
  if (keys_shown) {
    ImGui::TextUnformatted(kViewKeys);
  } else {
    ImGui::TextUnformatted("keys: K shows them, H hides this overlay");
  }
  const ImVec2 size = ImGui::GetWindowSize();
  ImGui::End();
  return {static_cast<int>(size.x), static_cast<int>(size.y)};
}

}  // namespace frontsteal::render
