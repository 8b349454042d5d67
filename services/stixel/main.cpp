// stixel service: DISPARITY (+ a recent earlier frame's EXTRINSICS as ground prior) -> STIXELS.
#include <chrono>

#include "message_convert.hpp"
#include "prior_selection.hpp"
#include "service_config.hpp"
#include "stixel_estimator.hpp"

using namespace nerv;

namespace {

int serve(ServiceConfig& config) {
  const stixel::Params params = stixel::readParams(config.section());
  int queue = 2;
  config.section().get("queue", queue, 1, 100);
  float min_prior_confidence = 0.3f;
  config.section().get("min_prior_confidence", min_prior_confidence, 0.0, 1.0);
  int max_prior_age_frames = 30;
  config.section().get("max_prior_age_frames", max_prior_age_frames, 0, 100000);
  // ... and in capture time: a short earlier drive's seqs are counted through again
  // by the next one, minutes later (0: no limit in time).
  int max_prior_age_ms = 3000;
  config.section().get("max_prior_age_ms", max_prior_age_ms, 0, 3600000);
  // A frame with more unobserved strips than this share counts as an error
  // (health "degraded"). Measured (bench_detection "observed free space"): KITTI
  // 0926 8-11 of 249 strips (the image borders), the synthetic sets 12-73 (wet
  // roads' puddles), a half-blinded view 120 and more.
  float max_unobserved_fraction = 0.4f;
  config.section().get("max_unobserved_fraction", max_unobserved_fraction, 0.0, 1.0);
  config.finish();

  Node node(config.nodeOptions());
  stixel::PriorSelection priors(max_prior_age_frames, int64_t{max_prior_age_ms} * 1000);
  cv::Mat disparity;
  warmUp(config, [&](const WarmupSize& size) {
    const StereoCamera cam = warmupCamera(size);
    stixel::estimateStixels(warmupDisparity(cam), cam, params);  // stateless: nothing carries over
  });

  node.subscribe<extrinsics_t>("EXTRINSICS", [&](const extrinsics_t& e) {
    if (Problem p = checkExtrinsics(e)) return node.error(p.counter, p.message);
    if (!e.valid || e.confidence < min_prior_confidence) return;
    priors.offer(e.header.seq, e.header.utime, {true, e.pitch_deg, e.roll_deg, e.height_m});
  }, 10);

  node.subscribe<disparity_t>("DISPARITY", [&](const disparity_t& msg) {
    if (!node.ownsFrame(msg.header.seq)) return;
    if (Problem p = checkDisparity(msg, node.options().limits))
      return node.error(p.counter, "frame " + std::to_string(msg.header.seq) + ": " + p.message);
    if (std::string why = decodeDisparity(msg, disparity); !why.empty())
      return node.error("bad_disparity", "frame " + std::to_string(msg.header.seq) + ": " + why);
    node.countIn();

    const auto start = std::chrono::steady_clock::now();
    const stixel::StixelResult result = stixel::estimateStixels(disparity, toCamera(msg.calib), params,
                                                                       priors.forFrame(msg.header.seq, msg.header.utime));
    const stixels_t out = stixelsMessage(
        msg.header, result.ground, result.stixels, result.hypotheses,
        std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count(),
        result.observed);
    if (!result.ground.valid) {
      node.error("no_ground", "frame " + std::to_string(msg.header.seq) + ": no ground found");
    } else if (const auto& o = result.observed;
               o.num_unobserved > max_unobserved_fraction * static_cast<float>(o.observed.size())) {
      // Much of the view unmeasured (glare, a covered lens, an object too near): the
      // missing boxes there say nothing about what stands there.
      node.error("unobserved", "frame " + std::to_string(msg.header.seq) + ": " +
                                   std::to_string(o.num_unobserved) + " of " + std::to_string(o.observed.size()) +
                                   " free-space strips have too little disparity: unknown, not free");
    }
    node.publish("STIXELS", out);
    node.countOut(msg.header.utime, out.processing_ms);
  }, queue);
  return node.spin();
}

}  // namespace

int main(int argc, char** argv) { return runService("stixel", argc, argv, serve); }
