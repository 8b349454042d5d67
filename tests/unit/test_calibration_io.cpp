#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "calibration_io.hpp"
#include "dataset.hpp"

using namespace nerv;
namespace fs = std::filesystem;

namespace {

const std::string kShared = NERV_SHARED_DATA;

fs::path tempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("nerv_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// KITTI 2011-09-26 colour cameras, as in ../shared/data/README.md.
void expectKitti0926(const StereoCamera& c) {
  EXPECT_NEAR(c.fx, 721.5377, 1e-4);
  EXPECT_NEAR(c.fy, 721.5377, 1e-4);
  EXPECT_NEAR(c.cx, 609.5593, 1e-4);
  EXPECT_NEAR(c.cy, 172.854, 1e-4);
  EXPECT_NEAR(c.baseline_m, 0.5327, 1e-3);
}

const char* kP2 = "7.215377e+02 0.000000e+00 6.095593e+02 4.485728e+01 0.000000e+00 7.215377e+02 1.728540e+02 2.163791e-01 0.000000e+00 0.000000e+00 1.000000e+00 2.745884e-03";
const char* kP3 = "7.215377e+02 0.000000e+00 6.095593e+02 -3.395242e+02 0.000000e+00 7.215377e+02 1.728540e+02 2.199936e+00 0.000000e+00 0.000000e+00 1.000000e+00 2.729905e-03";

}  // namespace

TEST(commonCalibrationIo, PlainYamlFromSharedData) {
  const std::string path = kShared + "/kitti_raw_0926_seq/calib.yaml";
  if (!fs::exists(path)) GTEST_SKIP() << "../shared/data is absent";
  const StereoCamera c = loadPlainCalibration(path);
  EXPECT_EQ(c.width, 1242);
  EXPECT_EQ(c.height, 375);
  expectKitti0926(c);
}

TEST(commonCalibrationIo, KittiObjectMatchesSharedExcerpt) {
  // The P_rect lines of kitti2015_000005 rewritten in the object format.
  const std::string excerpt = kShared + "/kitti2015_000005/calib_cam_to_cam_excerpt.txt";
  if (!fs::exists(excerpt)) GTEST_SKIP() << "../shared/data is absent";
  const fs::path dir = tempDir("object");
  write(dir / "000005.txt", std::string("P0: 1 0 0 0 0 1 0 0 0 0 1 0\nP2: ") + kP2 + "\nP3: " + kP3 + "\n");
  const StereoCamera c = loadKittiObjectCalibration((dir / "000005.txt").string(), 1242, 375);
  expectKitti0926(c);
  // The same numbers as the plain calib.yaml of that folder.
  const StereoCamera plain = loadPlainCalibration(kShared + "/kitti2015_000005/calib.yaml");
  EXPECT_NEAR(c.baseline_m, plain.baseline_m, 1e-3);
  fs::remove_all(dir);
}

TEST(commonCalibrationIo, KittiRawCamToCam) {
  const fs::path dir = tempDir("raw");
  write(dir / "calib_cam_to_cam.txt",
        std::string("calib_time: 09-Jan-2012 13:57:47\ncorner_dist: 9.950000e-02\n"
                    "S_rect_02: 1.242000e+03 3.750000e+02\nP_rect_02: ") + kP2 +
            "\nS_rect_03: 1.242000e+03 3.750000e+02\nP_rect_03: " + kP3 + "\n");
  const StereoCamera c = loadKittiRawCalibration((dir / "calib_cam_to_cam.txt").string());
  EXPECT_EQ(c.width, 1242);
  EXPECT_EQ(c.height, 375);
  expectKitti0926(c);
  fs::remove_all(dir);
}

TEST(commonCalibrationIo, ErrorsNameTheProblem) {
  const fs::path dir = tempDir("bad");
  EXPECT_THROW(loadPlainCalibration((dir / "missing.yaml").string()), CalibrationError);
  write(dir / "nan.yaml", "width: 10\nheight: 10\nfx: .nan\nfy: 1\ncx: 1\ncy: 1\nbaseline_m: 0.5\n");
  try {
    loadPlainCalibration((dir / "nan.yaml").string());
    FAIL() << "NaN focal length accepted";
  } catch (const CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("fx"), std::string::npos) << e.what();
  }
  write(dir / "nobase.yaml", "width: 10\nheight: 10\nfx: 1\nfy: 1\ncx: 1\ncy: 1\n");
  try {
    loadPlainCalibration((dir / "nobase.yaml").string());
    FAIL();
  } catch (const CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("baseline_m"), std::string::npos) << e.what();
  }
  write(dir / "P.txt", "P2: 1 2 3\n");
  EXPECT_THROW(loadKittiObjectCalibration((dir / "P.txt").string(), 10, 10), CalibrationError);
  write(dir / "neg.txt", std::string("P2: ") + kP3 + "\nP3: " + kP2 + "\n");  // swapped: B < 0
  EXPECT_THROW(loadKittiObjectCalibration((dir / "neg.txt").string(), 10, 10), CalibrationError);
  fs::remove_all(dir);
}

TEST(commonDataset, OpensSharedPlainLayout) {
  const std::string dir = kShared + "/kitti_raw_0926_seq";
  if (!fs::exists(dir)) GTEST_SKIP() << "../shared/data is absent";
  const Dataset ds = openDataset(dir);
  EXPECT_EQ(ds.layout, "plain");
  ASSERT_EQ(ds.frames.size(), 11u);
  EXPECT_EQ(ds.frames[0].name, "0000000000");
  EXPECT_FALSE(ds.frames[0].label_path.empty());
  expectKitti0926(ds.frames[3].camera);
}

TEST(commonDataset, MissingFolderAndCalibrationAreErrors) {
  EXPECT_THROW(openDataset("/nonexistent/nerv"), DatasetError);
  const fs::path dir = tempDir("nocalib");
  fs::create_directories(dir / "left");
  fs::create_directories(dir / "right");
  try {
    openDataset(dir.string());
    FAIL();
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find("calib.yaml"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}
