// nerv_misalign's right views moved by half a row with each interpolation it offers: the same
// pixels as OpenCV's warp with that kernel, the left views as they were, and an unknown kernel
// refused with exit 2.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "stereo_scene_texture.hpp"

namespace nerv {
namespace {

namespace fs = std::filesystem;

class toolsMisalignCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("nerv_misalign_cli_" + std::to_string(getpid()));
    fs::create_directories(dir_ / "in" / "left");
    fs::create_directories(dir_ / "in" / "right");
    left_ = stereo::multiScaleTexture(160, 96, 31);
    right_ = stereo::multiScaleTexture(160, 96, 32);
    cv::imwrite((dir_ / "in" / "left" / "000000.png").string(), left_);
    cv::imwrite((dir_ / "in" / "right" / "000000.png").string(), right_);
    std::ofstream(dir_ / "in" / "calib.yaml") << "width: 160\nheight: 96\nfx: 100\nfy: 100\ncx: 80\ncy: 48\n"
                                                 "baseline_m: 0.5\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs nerv_misalign into OUT; its exit status.
  int misalign(const std::string& out, const std::string& options) const {
    const std::string cmd = test::cliPath("nerv_misalign").string() + " --data " + (dir_ / "in").string() +
                            " --out " + (dir_ / out).string() + " " + options + " > /dev/null 2>&1";
    return WEXITSTATUS(std::system(cmd.c_str()));
  }
  cv::Mat read(const std::string& out, const char* side) const {
    return cv::imread((dir_ / out / side / "000000.png").string(), cv::IMREAD_UNCHANGED);
  }
  cv::Mat expected(int interpolation) const {
    const cv::Mat half_down = (cv::Mat_<double>(2, 3) << 1, 0, 0, 0, 1, 0.5);
    cv::Mat moved;
    cv::warpAffine(right_, moved, half_down, right_.size(), interpolation, cv::BORDER_REPLICATE);
    return moved;
  }

  fs::path dir_;
  cv::Mat left_, right_;
};

TEST_F(toolsMisalignCli, HalfARowWithEachKernel) {
  ASSERT_EQ(misalign("linear", "--rows 0.5"), 0);
  ASSERT_EQ(misalign("lanczos", "--rows 0.5 --interpolation lanczos"), 0);
  EXPECT_EQ(cv::norm(read("linear", "left"), left_, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(read("lanczos", "left"), left_, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(read("linear", "right"), expected(cv::INTER_LINEAR), cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(read("lanczos", "right"), expected(cv::INTER_LANCZOS4), cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(read("lanczos", "right"), read("linear", "right"), cv::NORM_INF), 0);
}

TEST_F(toolsMisalignCli, AnUnknownKernelIsRefused) {
  EXPECT_EQ(misalign("cubic", "--rows 0.5 --interpolation cubic"), 2);
  EXPECT_FALSE(fs::exists(dir_ / "cubic"));
}

}  // namespace
}  // namespace nerv
