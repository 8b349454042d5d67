// LatencyBreakdown: stage times from logger receive times, against hand-computed frames.
#include <gtest/gtest.h>

#include "json_writer.hpp"
#include "latency_breakdown.hpp"

using namespace nerv;

namespace {

// One frame captured at t0 [us]: channel arrivals [ms after capture] and processing [ms].
void addFrame(LatencyBreakdown& b, int64_t seq, int64_t t0, double frame, double disparity, double stixels,
              double normals, double detections, double matcher_ms, double stixel_ms, double snv_ms,
              double validator_ms) {
  auto at = [&](double ms) { return t0 + static_cast<int64_t>(ms * 1000); };
  b.add(seq, "STEREO_FRAME", at(frame), t0, -1);
  b.add(seq, "DISPARITY", at(disparity), t0, matcher_ms);
  b.add(seq, "STIXELS", at(stixels), t0, stixel_ms);
  b.add(seq, "SURFACE_NORMALS", at(normals), t0, snv_ms);
  b.add(seq, "DETECTIONS", at(detections), t0, validator_ms);
}

const LatencyBreakdown::Stage& stage(const std::string& name) {
  for (const auto& s : LatencyBreakdown::stages())
    if (s.name == name) return s;
  throw std::runtime_error("no stage " + name);
}

}  // namespace

TEST(toolsLatencyBreakdown, StageTimeIsOutputArrivalAfterTheLatestInput) {
  LatencyBreakdown b;
  // matcher: 2 -> 40 (35 ms of work, 3 ms rest); stixel: 40 -> 47 (5 + 2);
  // snv waits for STIXELS (47), answers at 52 (4 + 1); validator 52 -> 52.5 (0.2 + 0.3)
  addFrame(b, 0, 1000000, 2, 40, 47, 52, 52.5, 35, 5, 4, 0.2);
  const auto m = b.figures(stage("stereo_matcher"));
  EXPECT_EQ(m.frames, 1);
  EXPECT_NEAR(m.stage_p50, 38.0, 1e-6);
  EXPECT_NEAR(m.processing_p50, 35.0, 1e-6);
  EXPECT_NEAR(m.rest_p50, 3.0, 1e-6);
  EXPECT_NEAR(b.figures(stage("stixel")).rest_p50, 2.0, 1e-6);
  const auto s = b.figures(stage("snv_extrinsic"));
  EXPECT_NEAR(s.stage_p50, 5.0, 1e-6) << "measured from STIXELS, the later of its two inputs";
  EXPECT_NEAR(s.rest_p50, 1.0, 1e-6);
  EXPECT_NEAR(b.figures(stage("validator")).rest_p50, 0.3, 1e-6);
  EXPECT_NEAR(b.arrivalP50("DETECTIONS"), 52.5, 1e-6);
}

TEST(toolsLatencyBreakdown, MedianOverFramesAndIncompleteFramesLeftOut) {
  LatencyBreakdown b;
  addFrame(b, 0, 0, 1, 31, 40, 45, 46, 30, 5, 4, 0.1);        // matcher stage 30
  addFrame(b, 1, 100000, 1, 51, 60, 65, 66, 30, 5, 4, 0.1);   // 50: queued behind frame 0
  addFrame(b, 2, 200000, 1, 41, 50, 55, 56, 30, 5, 4, 0.1);   // 40
  b.add(3, "STEREO_FRAME", 300000, 300000, -1);                // lost in the matcher
  b.add(4, "DISPARITY", 400000, 390000, 30);                   // its frame was not logged
  const auto m = b.figures(stage("stereo_matcher"));
  EXPECT_EQ(m.frames, 3);
  EXPECT_NEAR(m.stage_p50, 40.0, 1e-6);
  EXPECT_NEAR(m.stage_p95, 50.0, 1e-6);
  EXPECT_NEAR(m.rest_p50, 10.0, 1e-6);
  EXPECT_EQ(b.figures(stage("stixel")).frames, 3) << "frame 4's DISPARITY has no STIXELS";
}

TEST(toolsLatencyBreakdown, TheFirstAnswerOfAFrameCounts) {
  LatencyBreakdown b;
  addFrame(b, 0, 0, 1, 31, 40, 45, 46, 30, 5, 4, 0.1);
  b.add(0, "DISPARITY", 90000, 0, 30);  // a second shard answering late
  EXPECT_NEAR(b.figures(stage("stereo_matcher")).stage_p50, 30.0, 1e-6);
}

TEST(toolsLatencyBreakdown, JsonNamesEveryStageAndChannel) {
  LatencyBreakdown b;
  addFrame(b, 0, 0, 2, 40, 47, 52, 52.5, 35, 5, 4, 0.2);
  JsonWriter j(false);
  j.beginObject();
  b.writeJson(j);
  j.endObject();
  const std::string s = j.str();
  for (const char* k : {"latency_breakdown_ms", "arrival_p50", "STEREO_FRAME", "DETECTIONS", "stereo_matcher",
                        "stixel", "snv_extrinsic", "validator", "rest_p50", "processing_p50"})
    EXPECT_NE(s.find(std::string("\"") + k + "\""), std::string::npos) << k;
  EXPECT_NE(b.text().find("stereo_matcher 38.0 = 35.0 + 3.0"), std::string::npos) << b.text();
}
