// Sequential and two-thread checks of core/component_publication.hpp: publication at the last surface only,
// slot choice, and the reclamation wait (the driver does not reuse a slot the pusher still holds), with the
// planted defect as negative control. Interleavings are the model checker's job (models_check/).
#include <atomic>
#include <chrono>
#include <thread>

#include <catch2/catch.hpp>

#include "core/component_publication.hpp"
#include "core/publication_policies.hpp"
#include "core/std_backend.hpp"

namespace fs = frontsteal;

template <class Policy>
using Publication = fs::ComponentPublication<fs::StdBackend, Policy>;

TEST_CASE("a component is published when its last surface is finished, not before") {
  Publication<fs::PublicationOrders> p({3, 1}, 3);
  p.prepare_frame();
  const fs::SlotIndex back = p.back_slot(0);
  CHECK_FALSE(p.finish_surface(0));
  CHECK_FALSE(p.finish_surface(0));
  p.begin_update();
  CHECK(p.read(0) == Publication<fs::PublicationOrders>::kNothing);  // two of three surfaces: nothing yet
  p.end_update();
  CHECK(p.finish_surface(0));
  CHECK(p.finish_surface(1));
  p.begin_update();
  CHECK(p.read(0) == back);
  p.end_update();
}

TEST_CASE("the next frame writes a slot other than the published one") {
  Publication<fs::PublicationOrders> p({1}, 2);
  for (int frame = 0; frame < 6; ++frame) {
    p.prepare_frame();
    p.begin_update();
    const fs::SlotIndex shown = p.read(0);
    p.end_update();
    CHECK(p.back_slot(0) != shown);
    CHECK(p.finish_surface(0));
  }
}

// With two slots, the slot retired while the pusher is inside an update is the only candidate for the next
// frame: the driver must wait until the pusher ends that update. The defect reuses it at once. The pusher holds
// its update for up to `patience`, or until the driver has prepared: a sound driver never prepares before the
// update ends (so 50 ms show a wait), while a defective one does as soon as its thread gets a core, however
// late the machine's load lets that be (so its bound is long and never reached).
template <class Policy>
bool driver_waits_for_the_pusher(std::chrono::milliseconds patience) {
  Publication<Policy> p({1}, 2);
  p.prepare_frame();
  p.finish_surface(0);  // frame 1 published: slot a
  p.begin_update();     // the pusher holds a …
  const fs::SlotIndex held = p.read(0);
  p.prepare_frame();
  p.finish_surface(0);  // frame 2 publishes b and retires a, stamped with the update in progress
  std::atomic<bool> prepared{false};
  std::thread driver([&] {
    p.prepare_frame();  // frame 3 needs a
    prepared.store(true);
  });
  const auto deadline = std::chrono::steady_clock::now() + patience;
  while (!prepared.load() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const bool reused_early = prepared.load();
  p.end_update();  // … until here
  driver.join();
  CHECK(p.back_slot(0) == held);
  return !reused_early;
}

TEST_CASE("a retired slot is reused only after the pusher has passed a later update") {
  CHECK(driver_waits_for_the_pusher<fs::PublicationOrders>(std::chrono::milliseconds(50)));
}

TEST_CASE("negative control: without the grace period the slot is reused under the pusher") {
  CHECK_FALSE(driver_waits_for_the_pusher<fs::BrokenReuseWithoutGrace>(std::chrono::seconds(60)));
}

TEST_CASE("negative control: publishing each surface exposes a half-written component") {
  Publication<fs::BrokenPublishEachSurface> p({2}, 3);
  p.prepare_frame();
  CHECK(p.finish_surface(0));  // published after one of two surfaces: torn
}
