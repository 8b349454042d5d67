// nerv_eval_disparity --log on a hand-made log: each DISPARITY event is scored against the
// ground-truth frame its frame_id names, also when nerv_source's "<folder>/<frame>" form names
// it, each seq once, and with --from-seq only the later frames.
#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "lcm_test_log.hpp"
#include "message_convert.hpp"
#include "nerv/disparity_t.hpp"

namespace fs = std::filesystem;
using namespace nerv;

namespace {

// A 64 x 32 frame at disparity `d` everywhere, named by frame_id, as the stereo_matcher sends it.
disparity_t frame(int seq, const std::string& frame_id, float d) {
  disparity_t msg{};
  msg.header.seq = seq;
  msg.header.frame_id = frame_id;
  msg.calib.width = 64, msg.calib.height = 32;
  msg.calib.fx = msg.calib.fy = 100, msg.calib.cx = 32, msg.calib.cy = 16, msg.calib.baseline_m = 0.5;
  msg.calib.rectified = true;
  msg.algorithm = "hand_made";
  encodeDisparity(cv::Mat(32, 64, CV_32F, cv::Scalar(d)), "u16le", msg);
  return msg;
}

void writeLog(const fs::path& path, const std::vector<disparity_t>& frames) {
  ASSERT_TRUE(test::writeLcmLog(path.string(), "DISPARITY", frames));
}

class toolsEvalDisparityCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(cli)) GTEST_SKIP() << cli << " not built";
    // One frame, 000000, its ground truth 20 px everywhere (KITTI's 16-bit PNG: 256 per px).
    for (const char* sub : {"left", "right", "disp_gt"}) fs::create_directories(tmp / sub);
    const cv::Mat gray(32, 64, CV_8UC1, cv::Scalar(128));
    cv::imwrite((tmp / "left" / "000000.png").string(), gray);
    cv::imwrite((tmp / "right" / "000000.png").string(), gray);
    cv::imwrite((tmp / "disp_gt" / "000000.png").string(), cv::Mat(32, 64, CV_16UC1, cv::Scalar(20 * 256)));
  }
  void TearDown() override { fs::remove_all(tmp); }
  std::string base() const {
    return cli.string() + " --data " + tmp.string() + " --log " + (tmp / "run.lcmlog").string();
  }
  const fs::path cli = test::cliPath("nerv_eval_disparity");
  const fs::path tmp = fs::temp_directory_path() / ("nerv_test_eval_disparity_cli_" + std::to_string(getpid()));
};

}  // namespace

TEST_F(toolsEvalDisparityCli, NervSourceFrameIdsEachSeqOnceAndFromSeq) {
  // seq 3: 10 px off everywhere (all bad); seq 4: exact; seq 4 again (a replay of the log's
  // frame, here 10 px off): not counted a second time; seq 5 names no frame of the set.
  writeLog(tmp / "run.lcmlog", {frame(3, "kitti_seq/000000", 30), frame(4, "kitti_seq/000000", 20),
                                frame(4, "kitti_seq/000000", 30), frame(5, "kitti_seq/000007", 20)});
  const std::string all = test::squeezeSpaces(test::runCli(base() + " 2>&1"));
  EXPECT_NE(all.find("hand_made 2 D1 50.00% 100.0%"), std::string::npos) << all;
  EXPECT_NE(all.find("skipped: 0 undecodable, 1 naming no ground-truth frame of the same size"), std::string::npos)
      << all;
  const std::string later = test::squeezeSpaces(test::runCli(base() + " --from-seq 4 2>&1"));
  EXPECT_NE(later.find("hand_made 1 D1 0.00% 100.0%"), std::string::npos) << later;
  // The id as a whole, as an older log wrote it, is found too.
  writeLog(tmp / "run.lcmlog", {frame(1, "000000", 20)});
  const std::string plain = test::squeezeSpaces(test::runCli(base() + " 2>&1"));
  EXPECT_NE(plain.find("hand_made 1 D1 0.00%"), std::string::npos) << plain;
}

// Every disparity half a pixel too small: no pixel wrong by D1, the subpixel error 0.5 px, and the
// bias column -0.5 px, the sign that tells an offset (a rig turned since calibration) apart.
TEST_F(toolsEvalDisparityCli, TheBiasColumnIsSigned) {
  writeLog(tmp / "run.lcmlog", {frame(1, "000000", 19.5f)});
  const std::string out = test::squeezeSpaces(test::runCli(base() + " 2>&1"));
  EXPECT_NE(out.find("hand_made 1 D1 0.00% 100.0% 0.500 -0.500"), std::string::npos) << out;
  EXPECT_NE(out.find("subpx bias ms/frame"), std::string::npos) << out;
}
