// Logs of several pipelines (a channel prefix per camera): which events the log tools read.
#include <gtest/gtest.h>
#include <unistd.h>
#include <lcm/lcm-cpp.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "lcm_test_log.hpp"
#include "log_summary.hpp"
#include "nerv/detections_t.hpp"
#include "nerv/health_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "pipeline_prefix.hpp"

using namespace nerv;
using nerv::test::appendLcmEvent;

TEST(pipelinePrefix, ChannelPrefixes) {
  EXPECT_EQ(nervChannelPrefix("FRONT_DISPARITY"), "FRONT_");
  EXPECT_EQ(nervChannelPrefix("DISPARITY"), "");
  EXPECT_EQ(nervChannelPrefix("REAR_NERV_HEALTH"), "REAR_");
  EXPECT_EQ(nervChannelPrefix("X_SURFACE_NORMALS"), "X_");
  EXPECT_FALSE(nervChannelPrefix("CAMERA_IMAGE").has_value());
  EXPECT_FALSE(nervChannelPrefix("DISPARITY_RAW").has_value());
  EXPECT_EQ(framePipelinePrefix("FRONT_STEREO_FRAME"), "FRONT_");
  EXPECT_FALSE(framePipelinePrefix("FRONT_NERV_HEALTH").has_value());
}

TEST(pipelinePrefix, TheFirstFrameChannelDecidesUnlessOneIsAskedFor) {
  PipelineSelection first;
  EXPECT_TRUE(first.take("NERV_HEALTH"));        // health: every pipeline's, kept by prefix
  EXPECT_TRUE(first.take("REAR_STEREO_FRAME"));  // decides
  EXPECT_FALSE(first.take("FRONT_STEREO_FRAME"));
  EXPECT_TRUE(first.take("REAR_DETECTIONS"));
  EXPECT_FALSE(first.take("FRONT_DETECTIONS"));
  EXPECT_TRUE(first.take("GPS"));  // no nerv channel
  EXPECT_EQ(first.selected(), "REAR_");
  EXPECT_EQ(first.prefixes(), (std::vector<std::string>{"REAR_", "FRONT_"}));
  EXPECT_EQ(first.note(), "this log holds 2 pipelines, by channel prefix: 'REAR_' (read here), 'FRONT_'; "
                          "choose one with --prefix P");

  PipelineSelection front(std::string("FRONT_"));
  EXPECT_FALSE(front.take("REAR_STEREO_FRAME"));
  EXPECT_TRUE(front.take("FRONT_STEREO_FRAME"));
  EXPECT_EQ(front.selected(), "FRONT_");

  PipelineSelection one;
  EXPECT_TRUE(one.take("STEREO_FRAME"));
  EXPECT_TRUE(one.take("DETECTIONS"));
  EXPECT_EQ(one.note(), "");  // one pipeline: nothing to say

  PipelineSelection absent(std::string("SIDE_"));
  absent.take("FRONT_STEREO_FRAME");
  EXPECT_THROW(absent.note(), std::runtime_error);
}

namespace {

// A camera's pipeline: `frames` STEREO_FRAME, DETECTIONS for the first `answered`, one health report.
void writePipeline(lcm::LogFile& log, const std::string& prefix, int frames, int answered, int64_t t0) {
  for (int s = 0; s < frames; ++s) {
    stereo_frame_t f{};
    f.header.seq = s;
    f.header.utime = t0 + s * 100000;
    f.header.frame_id = prefix + "frame" + std::to_string(s);
    appendLcmEvent(log, prefix + "STEREO_FRAME", f, f.header.utime + 1000);
    if (s >= answered) continue;
    detections_t d{};
    d.header = f.header;
    d.num_kept = 0;
    appendLcmEvent(log, prefix + "DETECTIONS", d, f.header.utime + 30000);
  }
  health_t h{};
  h.service = "validator";
  h.instance = "0";
  h.frames_in = answered;
  appendLcmEvent(log, prefix + "NERV_HEALTH", h, t0 + frames * 100000);
}

}  // namespace

// Two cameras whose seqs overlap: the front answered all 5 frames, the rear 2 of 5. Merged by
// seq (before 2026-12-07) the summary said "5 in, 5 out" and hid the rear's 3 lost frames.
TEST(pipelinePrefix, TheSummaryReadsOnePipelineOfATwoCameraLog) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("nerv_two_cameras_" + std::to_string(getpid()) + ".lcmlog")).string();
  {
    lcm::LogFile log(path, "w");
    ASSERT_TRUE(log.good());
    writePipeline(log, "FRONT_", 5, 5, 1000000000);
    writePipeline(log, "REAR_", 5, 2, 1000000000);
  }
  std::string text;
  const std::string first = summarizeLog(path, &text);
  EXPECT_NE(first.find("\"prefix\":\"FRONT_\",\"prefixes\":[\"FRONT_\",\"REAR_\"],\"frames_in\":5,\"frames_out\":5,"),
            std::string::npos) << first.substr(0, 200);
  EXPECT_EQ(text.rfind("this log holds 2 pipelines, by channel prefix: 'FRONT_' (read here), 'REAR_'", 0), 0u) << text;

  const std::string rear = summarizeLog(path, &text, std::string("REAR_"));
  EXPECT_NE(rear.find("\"prefix\":\"REAR_\",\"prefixes\":[\"FRONT_\",\"REAR_\"],\"frames_in\":5,\"frames_out\":2,"),
            std::string::npos) << rear.substr(0, 200);
  EXPECT_NE(rear.find("\"frames_without_detections\":[2,3,4]"), std::string::npos) << rear.substr(0, 300);
  EXPECT_NE(text.find("frames: 5 in, 2 out (3 without DETECTIONS)"), std::string::npos) << text;
  // the health of the pipeline read, not the other's (both are validator/0)
  EXPECT_NE(text.find(" in 2 out 0 dropped"), std::string::npos) << text;
  EXPECT_EQ(text.find(" in 5 out 0 dropped"), std::string::npos) << text;

  EXPECT_THROW(summarizeLog(path, nullptr, std::string("SIDE_")), std::runtime_error);
  std::filesystem::remove(path);
}
