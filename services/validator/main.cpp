// validator service: STIXELS + SURFACE_NORMALS (joined by seq) -> DETECTIONS.
// A STIXELS frame whose normals never come is still published, every
// hypothesis marked "unvalidated", so no frame disappears downstream. While
// snv_extrinsic is down (two frames expired without normals and none came since),
// frames are published at once instead of after join_timeout_ms each
// (partner_join.hpp), until normals come again or snv_extrinsic announces itself in
// NERV_HEALTH (it started: frames wait for its normals from then on).
#include <chrono>
#include <cstdio>

#include "message_convert.hpp"
#include "partner_join.hpp"
#include "service_config.hpp"
#include "validator.hpp"

using namespace nerv;

namespace {

int serve(ServiceConfig& config) {
  const validator::Params params = validator::readParams(config.section());
  const JoinSettings join_settings = readJoinSettings(config.section(), 5);
  config.finish();

  Node node(config.nodeOptions());

  auto publish = [&](const stixels_t& smsg, const surface_normals_t* nmsg) {
    node.countIn();
    const auto start = std::chrono::steady_clock::now();
    std::vector<Hypothesis> hypotheses;
    for (const auto& r : smsg.rois) hypotheses.push_back(fromMessage(r));
    std::vector<NormalStats> stats;
    if (nmsg)
      for (const auto& s : nmsg->rois) stats.push_back(fromMessage(s));
    const std::vector<Verdict> verdicts = validator::validate(hypotheses, stats, params);
    detections_t out{};
    out.header = smsg.header;
    out.num_kept = 0;
    for (size_t i = 0; i < hypotheses.size(); ++i) {
      out.detections.push_back(toDetection(hypotheses[i], verdicts[i]));
      out.num_kept += verdicts[i].kept ? 1 : 0;
      if (verdicts[i].label == "unvalidated") node.count("unvalidated_hypotheses");
    }
    out.num_detections = static_cast<int32_t>(out.detections.size());
    // What was not seen travels with what was found (detections_t).
    out.num_columns = smsg.num_columns;
    out.num_unobserved = smsg.num_unobserved;
    out.observed_share = smsg.observed_share;
    out.processing_ms = std::chrono::duration<float, std::milli>(
                            std::chrono::steady_clock::now() - start).count();
    node.publish("DETECTIONS", out);
    node.countOut(smsg.header.utime, out.processing_ms);
  };

  // Two frames in a row: a single lost SURFACE_NORMALS message is not snv_extrinsic being down
  // (with one, the frame or two then in flight would go out unvalidated as well).
  PartnerJoin<stixels_t, surface_normals_t> join(
      join_settings.capacity, join_settings.timeout_us, 2,
      {[&](const stixels_t& s, const surface_normals_t& n) { publish(s, &n); },
       [&](const stixels_t& s, Alone why) {
         if (why == Alone::NotWaiting) {  // snv_extrinsic is down: no use waiting
           node.error("missing_normals", "frame " + std::to_string(s.header.seq) +
                                             ": no SURFACE_NORMALS coming, hypotheses unvalidated at once");
           node.count("published_without_waiting");
         } else {
           node.error("missing_normals", "frame " + std::to_string(s.header.seq) +
                                             ": no SURFACE_NORMALS, hypotheses unvalidated");
         }
         publish(s, nullptr);
       },
       // Normals for a frame already published alone are late: counted, not joined again.
       [&](const surface_normals_t&) { node.count("late_normals"); },
       [&](const surface_normals_t& n) {
         node.countDropped();
         node.error("missing_stixels", "frame " + std::to_string(n.header.seq) + ": SURFACE_NORMALS without STIXELS");
       }});

  // A snv_extrinsic that starts announces itself in NERV_HEALTH before its first normals: from
  // then on frames wait for them again, so none goes out unvalidated while it starts.
  node.onPeerStarted("snv_extrinsic", [&](const std::string& host, int pid) {
    if (join.expectPartner())
      std::fprintf(stderr, "validator: snv_extrinsic started (host %s, pid %d): waiting for SURFACE_NORMALS again\n",
                   host.c_str(), pid);
  });
  node.subscribe<stixels_t>("STIXELS", [&](const stixels_t& msg) {
    if (!node.ownsFrame(msg.header.seq)) return;
    if (Problem p = checkStixels(msg, node.options().limits))
      return node.error(p.counter, "frame " + std::to_string(msg.header.seq) + ": " + p.message);
    join.pushA(msg.header.seq, msg, nowUtime());
  }, join_settings.queue);
  node.subscribe<surface_normals_t>("SURFACE_NORMALS", [&](const surface_normals_t& msg) {
    if (!node.ownsFrame(msg.header.seq)) return;
    if (Problem p = checkSurfaceNormals(msg))
      return node.error(p.counter, "frame " + std::to_string(msg.header.seq) + ": " + p.message);
    join.pushB(msg.header.seq, msg, nowUtime());
  }, join_settings.queue);
  node.onTick([&] { join.tick(nowUtime()); });
  return node.spin();
}

}  // namespace

int main(int argc, char** argv) { return runService("validator", argc, argv, serve); }
