// snv_extrinsic service: DISPARITY + STIXELS (joined by seq) -> EXTRINSICS + SURFACE_NORMALS.
#include <chrono>

#include "message_convert.hpp"
#include "seq_join.hpp"
#include "service_config.hpp"
#include "snv_extrinsic.hpp"

using namespace nerv;

namespace {

int serve(ServiceConfig& config) {
  const snv::Params params = snv::readParams(config.section());
  const JoinSettings join_settings = readJoinSettings(config.section(), 2);
  config.finish();

  Node node(config.nodeOptions());
  snv::SnvExtrinsicEstimator estimator(params);
  cv::Mat disparity;
  warmUp(config, [&](const WarmupSize& size) {
    // Its buffers are per instance, so the service's own estimator runs; the
    // pose filter then starts over, as if nothing had been seen.
    const StereoCamera cam = warmupCamera(size);
    estimator.process(warmupDisparity(cam), cam, warmupHypotheses(cam), warmupGround(cam));
    estimator.resetFilter();
  });

  auto process = [&](const disparity_t& dmsg, const stixels_t& smsg) {
    if (std::string why = decodeDisparity(dmsg, disparity); !why.empty())
      return node.error("bad_disparity", "frame " + std::to_string(dmsg.header.seq) + ": " + why);
    node.countIn();
    const auto start = std::chrono::steady_clock::now();
    std::vector<Hypothesis> rois;
    for (const auto& r : smsg.rois) rois.push_back(fromMessage(r));
    const snv::SnvResult result = estimator.process(disparity, toCamera(dmsg.calib), rois, fromMessage(smsg.ground));
    const float ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count();

    extrinsics_t ext;
    ext.header = dmsg.header;
    fillExtrinsics(result.pose, ext);
    ext.processing_ms = ms;
    const surface_normals_t normals = surfaceNormalsMessage(dmsg.header, result.interval_px, result.ground_samples,
                                                            result.ground_normal, result.rois, ms);
    node.publish("EXTRINSICS", ext);
    node.publish("SURFACE_NORMALS", normals);
    node.countOut(dmsg.header.utime, ms);
  };

  SeqJoin<disparity_t, stixels_t> join(
      join_settings.capacity, join_settings.timeout_us, process,
      [&](const std::optional<disparity_t>& d, const std::optional<stixels_t>& s) {
        const int64_t seq = d ? d->header.seq : s->header.seq;
        node.countDropped();
        node.error("join_timeout", "frame " + std::to_string(seq) + ": no " +
                                       (d ? "STIXELS" : "DISPARITY") + " with the same seq");
      });

  node.subscribe<disparity_t>("DISPARITY", [&](const disparity_t& msg) {
    if (!node.ownsFrame(msg.header.seq)) return;
    if (Problem p = checkDisparity(msg, node.options().limits))
      return node.error(p.counter, "frame " + std::to_string(msg.header.seq) + ": " + p.message);
    join.pushA(msg.header.seq, msg, nowUtime());
  }, join_settings.queue);
  node.subscribe<stixels_t>("STIXELS", [&](const stixels_t& msg) {
    if (!node.ownsFrame(msg.header.seq)) return;
    if (Problem p = checkStixels(msg, node.options().limits))
      return node.error(p.counter, "frame " + std::to_string(msg.header.seq) + ": " + p.message);
    join.pushB(msg.header.seq, msg, nowUtime());
  }, join_settings.queue + 2);
  node.onTick([&] { join.expire(nowUtime()); });
  return node.spin();
}

}  // namespace

int main(int argc, char** argv) { return runService("snv_extrinsic", argc, argv, serve); }
