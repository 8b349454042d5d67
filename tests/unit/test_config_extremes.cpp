// Every key of the stixel, snv_extrinsic and validator config sections set, one at a time,
// to each end of the range its readParams accepts (both values of a switch, every allowed
// word): the three stages run on a frame and give output a planner can read. A value the
// config accepts is a promise that it runs; one that cannot should be refused at start,
// naming its key. The frames: a rendered road with three boxes (always) and KITTI 0926's
// first frame with nerv_sgm's disparity (when ../shared/data is there).
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <utility>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "config.hpp"
#include "dataset.hpp"
#include "snv_extrinsic.hpp"
#include "stereo_matcher.hpp"
#include "stixel_estimator.hpp"
#include "synthetic_road_scene.hpp"
#include "validator.hpp"

using namespace nerv;

namespace {

struct Frame {
  std::string name;
  cv::Mat disparity;
  StereoCamera cam;
};

std::vector<Frame> frames() {
  std::vector<Frame> out;
  stixel::RoadScene s;
  s.boxes = {{9.0f, -4.0f, -2.0f, 1.5f}, {18.0f, -1.0f, 1.0f, 1.5f}, {30.0f, 3.0f, 7.0f, 2.5f}};
  const StereoCamera cam = stixel::kittiLikeCamera();
  out.push_back({"rendered road", stixel::renderDisparity(s, cam), cam});
  const std::string kitti = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
  if (std::filesystem::is_directory(kitti)) {
    const DatasetFrame f = openDataset(kitti).frames.at(0);
    cv::Mat d, c;
    stereo::StereoMatcher::create(stereo::Params{})
        ->compute(cv::imread(f.left_path, cv::IMREAD_GRAYSCALE), cv::imread(f.right_path, cv::IMREAD_GRAYSCALE), d, c);
    out.push_back({"KITTI 0926 " + f.name, d, f.camera});
  }
  return out;
}

// The values to try for a declared key: both ends of its range (a bound at infinity is
// taken as +-1e6), both values of a switch, every allowed word.
std::vector<std::string> extremes(const ConfigSection::Declared& k) {
  auto number = [&](double v, bool integer) {
    if (!std::isfinite(v)) v = v > 0 ? 1e6 : -1e6;
    std::ostringstream s;
    s.precision(17);
    if (integer)
      s << static_cast<long long>(v);
    else
      s << v;
    return s.str();
  };
  switch (k.kind) {
    case ConfigSection::Declared::kNumber: return {number(k.lo, false), number(k.hi, false)};
    case ConfigSection::Declared::kInteger: return {number(k.lo, true), number(k.hi, true)};
    case ConfigSection::Declared::kBool: return {"false", "true"};
    case ConfigSection::Declared::kText: return k.allowed;
  }
  return {};
}

// A value drawn within the declared range (a bound at infinity taken as +-1e3).
std::string randomValue(const ConfigSection::Declared& k, std::mt19937& rng) {
  auto bound = [](double v) { return std::isfinite(v) ? v : (v > 0 ? 1e3 : -1e3); };
  std::ostringstream s;
  s.precision(9);
  switch (k.kind) {
    case ConfigSection::Declared::kNumber:
      s << std::uniform_real_distribution<double>(bound(k.lo), bound(k.hi))(rng);
      return s.str();
    case ConfigSection::Declared::kInteger:
      s << std::uniform_int_distribution<long long>(static_cast<long long>(bound(k.lo)),
                                                    static_cast<long long>(bound(k.hi)))(rng);
      return s.str();
    case ConfigSection::Declared::kBool: return rng() % 2 ? "true" : "false";
    case ConfigSection::Declared::kText:
      return k.allowed.empty() ? std::string("x") : k.allowed[rng() % k.allowed.size()];
  }
  return "";
}

template <class Read>
std::map<std::string, ConfigSection::Declared> keysOf(const std::string& section, Read read) {
  ConfigSection c(YAML::Node(), section);
  read(c);
  return c.declared();
}

struct Params3 {
  stixel::Params stixel;
  snv::Params snv;
  validator::Params validator;
};

// The three stages on one frame; an empty string when the output is usable, else what is wrong.
std::string runStages(const Frame& f, const Params3& p) {
  const stixel::StixelResult st = stixel::estimateStixels(f.disparity, f.cam, p.stixel);
  snv::SnvExtrinsicEstimator snv_est(p.snv);
  const snv::SnvResult sn = snv_est.process(f.disparity, f.cam, st.hypotheses, st.ground);
  const std::vector<Verdict> vs = validator::validate(st.hypotheses, sn.rois, p.validator);
  const cv::Rect image(0, 0, f.cam.width, f.cam.height);
  for (const Hypothesis& h : st.hypotheses) {
    const cv::Rect b(h.box.x, h.box.y, h.box.w, h.box.h);
    if (b.width <= 0 || b.height <= 0 || (b & image) != b) return "hypothesis " + std::to_string(h.id) + " box outside the image";
    for (float v : {h.x_m, h.y_m, h.z_m, h.width_m, h.height_m, h.distance_m, h.nearest_z_m, h.disparity})
      if (!std::isfinite(v)) return "hypothesis " + std::to_string(h.id) + " has a non-finite field";
  }
  for (const Stixel& s : st.stixels)
    if (s.u < 0 || s.u + s.width > f.cam.width || s.top_row < 0 || s.bottom_row >= f.cam.height || s.top_row > s.bottom_row ||
        !std::isfinite(s.disparity) || !std::isfinite(s.depth_m))
      return "stixel at u " + std::to_string(s.u) + " outside the image or not finite";
  if (sn.rois.size() != st.hypotheses.size()) return "normal statistics for " + std::to_string(sn.rois.size()) + " of " +
                                                     std::to_string(st.hypotheses.size()) + " hypotheses";
  if (sn.pose.valid)
    for (float v : {sn.pose.pitch_deg, sn.pose.roll_deg, sn.pose.height_m, sn.pose.confidence})
      if (!std::isfinite(v)) return "a valid pose with a non-finite value";
  if (vs.size() != st.hypotheses.size()) return "verdicts for " + std::to_string(vs.size()) + " of " +
                                                std::to_string(st.hypotheses.size()) + " hypotheses";
  return "";
}

// The three stages on every frame with one config (`what` names it): each run gives usable
// output and throws nothing.
void expectStagesRun(const std::vector<Frame>& fr, const Params3& p, const std::string& what, int& runs) {
  for (const Frame& f : fr) {
    std::string problem;
    try {
      problem = runStages(f, p);
    } catch (const std::exception& e) {
      problem = std::string("threw: ") + e.what();
    }
    EXPECT_EQ(problem, "") << what << " on " << f.name;
    ++runs;
  }
}

template <class Read, class Set>
void walkSection(const std::string& section, Read read, Set set, const std::vector<Frame>& fr, int& runs,
                 int& refused) {
  for (const auto& [key, declared] : keysOf(section, read)) {
    for (const std::string& value : extremes(declared)) {
      YAML::Node node(YAML::NodeType::Map);
      node[key] = value;
      ConfigSection c(node, section);
      Params3 p;
      try {
        set(p, c);
        c.finish();
      } catch (const ConfigError& e) {
        // Within its own range but against a rule across keys (min below max): refused at
        // start, naming a key of the section, is what the config promises.
        const std::string what = e.what();
        EXPECT_NE(what.find("config key '" + section + "."), std::string::npos) << what;
        EXPECT_NE(what.find("must be below"), std::string::npos)
            << section << "." << key << " = " << value << " is inside its declared range but refused: " << what;
        ++refused;
        continue;
      }
      expectStagesRun(fr, p, section + "." + key + " = " + value, runs);
    }
  }
}

// The matcher's frame: KITTI 0926's first pair halved (a fifth of the time; the near field
// still runs), or a textured pair with a 9 px shift without the data.
std::pair<cv::Mat, cv::Mat> matcherPair() {
  cv::Mat left, right;
  const std::string kitti = std::string(NERV_SHARED_DATA) + "/kitti_raw_0926_seq";
  if (std::filesystem::is_directory(kitti)) {
    const DatasetFrame f = openDataset(kitti).frames.at(0);
    cv::resize(cv::imread(f.left_path, cv::IMREAD_GRAYSCALE), left, {}, 0.5, 0.5, cv::INTER_AREA);
    cv::resize(cv::imread(f.right_path, cv::IMREAD_GRAYSCALE), right, {}, 0.5, 0.5, cv::INTER_AREA);
  } else {
    cv::Mat wide(188, 640, CV_8UC1);
    cv::RNG(2).fill(wide, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(wide, wide, cv::Size(0, 0), 1.0);
    left = wide(cv::Rect(0, 0, 621, 188)).clone();
    right = wide(cv::Rect(9, 0, 621, 188)).clone();
  }
  return {left, right};
}

// One stereo_matcher config: refused at start naming a key of the section, or a map of the
// frame's size, disparities finite and within the search (or the near field's 256 px),
// confidences within 0..1.
void checkMatcher(const YAML::Node& node, const std::string& what, const cv::Mat& left, const cv::Mat& right,
                  int& runs, int& refused) {
  ConfigSection c(node, "stereo_matcher");
  stereo::Params p;
  try {
    p = stereo::readParams(c);
    c.finish();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("config key 'stereo_matcher."), std::string::npos) << e.what();
    ++refused;
    return;
  }
  cv::Mat disparity, confidence;
  try {
    stereo::StereoMatcher::create(p)->compute(left, right, disparity, confidence);
  } catch (const std::exception& e) {
    // What only the frame can refuse (a window larger than it) is said naming its key; the
    // service counts it as processing_failed and goes on with the next frame.
    EXPECT_NE(std::string(e.what()).find("config key 'stereo_matcher."), std::string::npos) << what << " threw: " << e.what();
    ++refused;
    return;
  }
  ++runs;
  ASSERT_EQ(disparity.size(), left.size()) << what;
  ASSERT_EQ(confidence.size(), left.size()) << what;
  const float reach = std::max(256.0f, static_cast<float>(p.min_disparity + p.num_disparities));
  int bad_disparity = 0, bad_confidence = 0;
  for (int y = 0; y < left.rows; ++y)
    for (int x = 0; x < left.cols; ++x) {
      const float d = disparity.at<float>(y, x), q = confidence.at<float>(y, x);
      bad_disparity += !(std::isfinite(d) && d >= 0.0f && d <= reach);
      bad_confidence += !(q >= 0.0f && q <= 1.0f);
    }
  EXPECT_EQ(bad_disparity, 0) << what;
  EXPECT_EQ(bad_confidence, 0) << what;
}

}  // namespace

TEST(configExtremes, EveryKeyAtEitherEndOfItsRangeRuns) {
  const std::vector<Frame> fr = frames();
  int runs = 0, refused = 0;
  walkSection("stixel", [](ConfigSection& c) { stixel::readParams(c); },
              [](Params3& p, ConfigSection& c) { p.stixel = stixel::readParams(c); }, fr, runs, refused);
  walkSection("snv_extrinsic", [](ConfigSection& c) { snv::readParams(c); },
              [](Params3& p, ConfigSection& c) { p.snv = snv::readParams(c); }, fr, runs, refused);
  walkSection("validator", [](ConfigSection& c) { validator::readParams(c); },
              [](Params3& p, ConfigSection& c) { p.validator = validator::readParams(c); }, fr, runs, refused);
  EXPECT_GT(runs, 300);
  std::printf("configExtremes: %d runs over %zu frame(s), %d values refused by a rule across keys\n", runs,
              fr.size(), refused);
}

TEST(configExtremes, TheMatcherAtEitherEndOfEveryKeyRuns) {
  // The same for the stereo_matcher section (checkMatcher).
  const auto [left, right] = matcherPair();
  const auto keys = keysOf("stereo_matcher", [](ConfigSection& c) { stereo::readParams(c); });
  int runs = 0, refused = 0;
  for (const auto& [key, declared] : keys)
    for (const std::string& value : extremes(declared)) {
      YAML::Node node(YAML::NodeType::Map);
      node[key] = value;
      checkMatcher(node, "stereo_matcher." + key + " = " + value, left, right, runs, refused);
    }
  EXPECT_GT(runs, 40);
  std::printf("configExtremes: the matcher ran %d settings, %d refused by a rule across keys\n", runs, refused);
}

TEST(configExtremes, RandomCombinationsOfKeysRun) {
  // Keys interact (a tolerance against a height, a window against a range): 150 configs of
  // six keys each, drawn at random within their ranges (fixed seed), for the three stages
  // together; a config that a rule across keys refuses is counted, any other must run.
  const std::vector<Frame> fr = frames();
  const auto sx = keysOf("stixel", [](ConfigSection& c) { stixel::readParams(c); });
  const auto sn = keysOf("snv_extrinsic", [](ConfigSection& c) { snv::readParams(c); });
  const auto va = keysOf("validator", [](ConfigSection& c) { validator::readParams(c); });
  std::mt19937 rng(20261207);
  int runs = 0, refused = 0;
  auto pick = [&](const std::map<std::string, ConfigSection::Declared>& keys, YAML::Node& node) {
    auto it = keys.begin();
    std::advance(it, static_cast<long>(rng() % keys.size()));
    node[it->first] = randomValue(it->second, rng);
  };
  for (int i = 0; i < 150; ++i) {
    YAML::Node a(YAML::NodeType::Map), b(YAML::NodeType::Map), c(YAML::NodeType::Map);
    for (int j = 0; j < 2; ++j) pick(sx, a), pick(sn, b), pick(va, c);
    std::ostringstream what;
    what << "stixel " << YAML::Dump(a) << " | snv_extrinsic " << YAML::Dump(b) << " | validator " << YAML::Dump(c);
    Params3 p;
    try {
      ConfigSection cs(a, "stixel"), cn(b, "snv_extrinsic"), cv(c, "validator");
      p.stixel = stixel::readParams(cs);
      p.snv = snv::readParams(cn);
      p.validator = validator::readParams(cv);
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("must be below"), std::string::npos) << what.str() << ": " << e.what();
      ++refused;
      continue;
    }
    expectStagesRun(fr, p, what.str(), runs);
  }
  EXPECT_GT(runs, 100);
  std::printf("configExtremes: %d runs of random combinations, %d refused by a rule across keys\n", runs, refused);
}

TEST(configExtremes, RandomCombinationsOfMatcherKeysRun) {
  // 100 stereo_matcher configs of four keys each, drawn within their ranges (fixed seed); most
  // are refused at start (sgm_p2 against the census window's bits, the window's size).
  const auto [left, right] = matcherPair();
  const auto keys = keysOf("stereo_matcher", [](ConfigSection& c) { stereo::readParams(c); });
  std::mt19937 rng(7122026);
  int runs = 0, refused = 0;
  for (int i = 0; i < 100; ++i) {
    YAML::Node node(YAML::NodeType::Map);
    for (int j = 0; j < 4; ++j) {
      auto it = keys.begin();
      std::advance(it, static_cast<long>(rng() % keys.size()));
      node[it->first] = randomValue(it->second, rng);
    }
    checkMatcher(node, "stereo_matcher " + YAML::Dump(node), left, right, runs, refused);
  }
  EXPECT_GT(runs, 15);
  std::printf("configExtremes: the matcher ran %d random combinations, %d refused (at start, or by the frame naming the key)\n", runs, refused);
}
