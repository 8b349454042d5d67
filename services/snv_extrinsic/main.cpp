// snv_extrinsic service: DISPARITY + STIXELS (joined by seq) -> EXTRINSICS + SURFACE_NORMALS.
// While the stixel stage is down (two frames in a row without STIXELS and none since,
// partner_join.hpp) the camera pose goes on from the disparity alone: EXTRINSICS
// at once for every frame, without the stixel stage's ground model (on KITTI 0926 and
// four synthetic sets within 4 mm, 0.03 deg of pitch and 0.21 deg of roll of the pose
// with it), and no SURFACE_NORMALS, which only serve the hypotheses in STIXELS. A stixel
// stage that starts announces itself in NERV_HEALTH: frames wait for its STIXELS from then on.
#include <chrono>
#include <cstdio>

#include "message_convert.hpp"
#include "partner_join.hpp"
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

  // smsg null: the frame goes on alone (no STIXELS coming): pose only.
  auto process = [&](const disparity_t& dmsg, const stixels_t* smsg) {
    if (std::string why = decodeDisparity(dmsg, disparity); !why.empty())
      return node.error("bad_disparity", "frame " + std::to_string(dmsg.header.seq) + ": " + why);
    node.countIn();
    const auto start = std::chrono::steady_clock::now();
    std::vector<Hypothesis> rois;
    if (smsg)
      for (const auto& r : smsg->rois) rois.push_back(fromMessage(r));
    const snv::SnvResult result = estimator.process(disparity, toCamera(dmsg.calib), rois,
                                                    smsg ? fromMessage(smsg->ground) : GroundModel{});
    const float ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count();

    extrinsics_t ext{};
    ext.header = dmsg.header;
    fillExtrinsics(result.pose, ext);
    ext.processing_ms = ms;
    const surface_normals_t normals = surfaceNormalsMessage(dmsg.header, result.interval_px, result.ground_samples,
                                                            result.ground_normal, result.rois, ms);
    node.publish("EXTRINSICS", ext);
    if (smsg) node.publish("SURFACE_NORMALS", normals);
    node.countOut(dmsg.header.utime, ms);
  };

  // Two frames in a row: a single lost STIXELS message is not the stixel stage being down.
  PartnerJoin<disparity_t, stixels_t> join(
      join_settings.capacity, join_settings.timeout_us, 2,
      {[&](const disparity_t& d, const stixels_t& s) { process(d, &s); },
       // Its STIXELS never came, or are not coming: the camera pose still goes out.
       [&](const disparity_t& d, Alone why) {
         if (why == Alone::Waited)
           node.error("join_timeout", "frame " + std::to_string(d.header.seq) +
                                          ": no STIXELS with the same seq, camera pose from the disparity alone");
         else if (why == Alone::NotWaiting)  // the stixel stage is down: no use waiting
           node.error("missing_stixels", "frame " + std::to_string(d.header.seq) +
                                             ": no STIXELS coming, camera pose from the disparity alone");
         node.count("pose_without_stixels");
         process(d, nullptr);
       },
       // STIXELS for a frame whose pose went out alone are late: counted, not joined again.
       [&](const stixels_t&) { node.count("late_stixels"); },
       [&](const stixels_t& s) {
         node.countDropped();
         node.error("join_timeout", "frame " + std::to_string(s.header.seq) + ": no DISPARITY with the same seq");
       }});

  // A stixel stage that starts announces itself in NERV_HEALTH before its first STIXELS: from
  // then on frames wait for them again, so no frame's normals are lost while it starts.
  node.onPeerStarted("stixel", [&](const std::string& host, int pid) {
    if (join.expectPartner())
      std::fprintf(stderr, "snv_extrinsic: stixel started (host %s, pid %d): waiting for STIXELS again\n",
                   host.c_str(), pid);
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
  node.onTick([&] { join.tick(nowUtime()); });
  return node.spin();
}

}  // namespace

int main(int argc, char** argv) { return runService("snv_extrinsic", argc, argv, serve); }
