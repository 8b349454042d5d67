// Bad scenes fail with one line naming the problem; the CLI prints it as
// "nerv_synth: <message>" and exits with status 2.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene_yaml.hpp"
#include "sequence.hpp"

namespace {

using namespace nerv::synth;
namespace fs = std::filesystem;

// The SceneError message of a scene, "" if it loads.
std::string problem(const std::string& yaml) {
  try {
    SceneSequence seq(parseScene(yaml, "test"));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void expectProblem(const std::string& yaml, const std::string& needle) {
  const std::string msg = problem(yaml);
  EXPECT_NE(msg.find(needle), std::string::npos) << "message: '" << msg << "' for\n" << yaml;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
}

TEST(synthErrors, UnknownSceneKeyIsNamed) {
  expectProblem("camera: {focal: 700}\n", "camera.focal");
  expectProblem("weather: rain\n", "'weather'");
  expectProblem("obstacles:\n  - {class: car, distance_m: 20, colour_name: red}\n", "obstacles[0].colour_name");
  expectProblem("traps: {wet_patches: [{distance_m: 10, depth_m: 1}]}\n", "traps.wet_patches[0].depth_m");
  expectProblem("road: {lanes_right: 40}\n", "road.lanes_right");
  expectProblem("obstacles:\n  - {class: tank}\n", "obstacles[0].class");
}

TEST(synthErrors, ImpossiblePlacementIsNamed) {
  expectProblem("obstacles:\n  - {class: car, distance_m: -5}\n", "behind the camera");
  expectProblem("obstacles:\n  - {class: car, distance_m: 0}\n", "behind the camera");
  expectProblem("obstacles:\n  - {class: pole, distance_m: 12}\n  - {class: pedestrian, distance_m: 9, elevation_m: -0.5}\n",
                "obstacle 1 (Pedestrian) is below the road");
}

TEST(synthErrors, BadCalibrationIsNamed) {
  expectProblem("camera: {fx: 0}\n", "focal length");
  expectProblem("camera: {fx: -721.5}\n", "focal length");
  expectProblem("camera: {baseline_m: 0}\n", "baseline");
  expectProblem("camera: {baseline_m: -0.54}\n", "baseline");
  EXPECT_EQ(problem("camera: {fx: 500, baseline_m: 0.3}\n"), "");
}

// build/tests/test_synth_errors -> build/bin/nerv_synth
fs::path cliPath() {
  return fs::canonical("/proc/self/exe").parent_path().parent_path() / "bin" / "nerv_synth";
}

TEST(synthErrors, CliPrintsTheMessageAndExitsWith2) {
  const fs::path cli = cliPath();
  if (!fs::exists(cli)) GTEST_SKIP() << cli << " not built";
  const fs::path tmp = fs::temp_directory_path() / ("nerv_test_synth_cli_" + std::to_string(getpid()));
  fs::create_directories(tmp);
  const fs::path yaml = tmp / "bad.yaml", err = tmp / "stderr.txt";
  struct Case {
    std::string yaml, needle;
  };
  for (const Case& c : {Case{"camera: {focal: 700}\n", "camera.focal"},
                        Case{"obstacles:\n  - {class: car, distance_m: -3}\n", "behind the camera"},
                        Case{"camera: {baseline_m: 0}\n", "baseline"}}) {
    std::ofstream(yaml) << c.yaml;
    const std::string cmd = cli.string() + " --scene " + yaml.string() + " --frames 1 --out " +
                            (tmp / "out").string() + " 2> " + err.string();
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2);
    std::ifstream in(err);
    std::string first, rest;
    std::getline(in, first);
    EXPECT_EQ(first.rfind("nerv_synth: ", 0), 0u) << first;
    EXPECT_NE(first.find(c.needle), std::string::npos) << first;
    EXPECT_FALSE(std::getline(in, rest)) << "more than one line: " << rest;
  }
  // A missing scene name is an error too, and nothing is written.
  const int status = std::system((cli.string() + " --scene no_such_scene --frames 1 --out " +
                                  (tmp / "out2").string() + " 2> /dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_FALSE(fs::exists(tmp / "out2"));
  fs::remove_all(tmp);
}

}  // namespace
