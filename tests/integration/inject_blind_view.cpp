// Test helper: publishes DISPARITY frames of a rendered road with a car - one
// seen whole, one with its left half blinded (no disparity, as under glare or
// a covered lens) - and checks over LCM what the stixel and validator
// services make of them: STIXELS and DETECTIONS say how much of the free space
// was measured, the blinded frame reads as unknown rather than free, and the
// stixel service counts it ("unobserved") in NERV_HEALTH.
// Exit 0 when every expectation holds; prints what it saw either way.
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <map>
#include <string>

#include "inject_bus.hpp"
#include "message_convert.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/health_t.hpp"
#include "nerv/stixels_t.hpp"
#include "synthetic_road_scene.hpp"

using namespace nerv;

namespace {

struct Listener {
  std::map<std::string, int64_t> stixel_counters;
  std::map<int64_t, stixels_t> stixels;
  std::map<int64_t, detections_t> detections;
  void health(const lcm::ReceiveBuffer*, const std::string&, const health_t* h) {
    if (h->service != "stixel") return;
    for (int i = 0; i < h->num_counters; ++i) stixel_counters[h->counter_names[i]] = h->counter_values[i];
    stixel_counters["(reported)"] = 1;
  }
  void onStixels(const lcm::ReceiveBuffer*, const std::string&, const stixels_t* s) { stixels[s->header.seq] = *s; }
  void onDetections(const lcm::ReceiveBuffer*, const std::string&, const detections_t* d) {
    detections[d->header.seq] = *d;
  }
};

}  // namespace

int main(int argc, char** argv) {
  Listener l;
  const auto bus = test::openBus(argc, argv);
  if (!bus) return 2;
  lcm::LCM& lcm = *bus;
  lcm.subscribe("NERV_HEALTH", &Listener::health, &l);
  lcm.subscribe("STIXELS", &Listener::onStixels, &l);
  lcm.subscribe("DETECTIONS", &Listener::onDetections, &l);
  test::handleUntil(lcm, std::chrono::seconds(10), [&] { return l.stixel_counters.count("(reported)") > 0; });

  const StereoCamera cam = stixel::kittiLikeCamera();
  stixel::RoadScene scene;
  scene.boxes.push_back({15.0f, 2.0f, 4.0f, 1.5f});  // a car ahead on the right, 15 m
  const cv::Mat seen = stixel::renderDisparity(scene, cam);
  cv::Mat blind = seen.clone();
  blind.colRange(0, 600).setTo(0.0f);  // 120 of 249 strips without disparity; the car (705-801) seen
  const int64_t utime = std::chrono::duration_cast<std::chrono::microseconds>(
                            std::chrono::system_clock::now().time_since_epoch()).count();
  for (int64_t seq : {1, 2}) {
    disparity_t d;
    d.header.seq = seq;
    d.header.utime = utime + seq;
    d.header.frame_id = seq == 1 ? "inject/seen" : "inject/blind";
    d.calib = toCalibration(cam);
    encodeDisparity(seq == 1 ? seen : blind, "u16le", d);
    encodeConfidence(cv::Mat(), d);
    d.algorithm = "rendered";
    d.min_disparity = 0;
    d.max_disparity = 128;
    d.processing_ms = 0;
    lcm.publish("DISPARITY", &d);
    test::handleFor(lcm, std::chrono::milliseconds(200));
  }

  auto expectations = [&] {
    if (!l.stixels.count(1) || !l.stixels.count(2) || !l.detections.count(1) || !l.detections.count(2))
      return false;
    const stixels_t &a = l.stixels[1], &b = l.stixels[2];
    const detections_t &da = l.detections[1], &db = l.detections[2];
    return a.num_columns == 249 && a.column_width_px == 5 && a.num_unobserved == 0 && a.observed_share > 0.99f &&
           b.num_columns == 249 && b.num_unobserved == 120 && b.observed_share < 0.6f && b.observed[0] == 0.0f &&
           b.observed[248] == 1.0f && da.num_columns == 249 && da.num_unobserved == 0 && db.num_unobserved == 120 &&
           db.observed_share == b.observed_share && da.num_detections >= 1 && db.num_detections >= 1 &&
           l.stixel_counters["unobserved"] >= 1;
  };
  test::handleUntil(lcm, std::chrono::seconds(10), expectations, 100);

  for (const auto& [seq, s] : l.stixels)
    std::printf("STIXELS %lld: %d strips of %d px, %d unobserved, share %.3f\n", (long long)seq, s.num_columns,
                s.column_width_px, s.num_unobserved, s.observed_share);
  for (const auto& [seq, d] : l.detections)
    std::printf("DETECTIONS %lld: %d kept of %d, %d of %d strips unobserved, share %.3f\n", (long long)seq,
                d.num_kept, d.num_detections, d.num_unobserved, d.num_columns, d.observed_share);
  for (const auto& [name, value] : l.stixel_counters) std::printf("stixel.%s = %lld\n", name.c_str(), (long long)value);
  if (!expectations()) {
    std::fprintf(stderr, "inject: the blinded view was not reported as unobserved\n");
    return 1;
  }
  return 0;
}
