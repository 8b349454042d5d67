// What each service does with one received message, step for step as lcm_node's
// subscribe and the service's main.cpp do it: decode, check, convert, run the
// algorithm, build the outgoing message. Shared by the mutation test
// (tests/unit/test_common_message_fuzz.cpp) and the libFuzzer harnesses
// (tests/fuzz/fuzz_*.cpp), so both exercise the same path.
//
// The promise under test (README "Bad input"): a bad message is rejected with a
// named counter; an accepted one is processed without an exception and gives
// outputs the next stage accepts (finite numbers where the message says so).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "message_check.hpp"
#include "message_convert.hpp"
#include "nerv/disparity_t.hpp"
#include "nerv/extrinsics_t.hpp"
#include "nerv/stereo_frame_t.hpp"
#include "nerv/stixels_t.hpp"
#include "nerv/surface_normals_t.hpp"

namespace nerv::fuzz {

struct Outcome {
  bool accepted = false;  // passed decode and every check, and was processed
  std::string counter;    // the health counter it was rejected under ("" = accepted)
  std::string message;    // the one-line error
  std::string bug;        // not empty: a broken promise (exception after the checks, bad output)
};

// A small scene (camera, textured stereo pair, exact disparity) and the valid
// messages the pipeline makes of it, encoded as on the bus.
struct Scene {
  StereoCamera camera;
  cv::Mat left, right;  // CV_8U gray, rectified
  cv::Mat disparity;    // CV_32F, exact (rendered road and boxes)
  stereo_frame_t frame;      // gray8 images
  disparity_t disparity_msg; // u16le, with confidence
  stixels_t stixels;         // estimateStixels on the disparity
  surface_normals_t normals; // the snv estimator on disparity + stixels
  extrinsics_t extrinsics;   // idem
};
const Scene& scene();

template <class T>
std::vector<uint8_t> encode(const T& msg) {
  std::vector<uint8_t> bytes(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// The scene's boxes without the road: no v-disparity fit, so the stixel stage
// falls back to the EXTRINSICS prior.
const cv::Mat& weakGroundDisparity();

// The limits the paths run with (small: absurd sizes are cheap to reject).
Limits fuzzLimits();

// Valid encoded messages of one received type ("stereo_frame", "disparity",
// "stixels", "surface_normals", "extrinsics"): the seeds of the mutations.
std::vector<std::vector<uint8_t>> seedMessages(const std::string& type);

// One service path per received message type. Each keeps no state between calls.
Outcome receiveStereoFrame(const uint8_t* data, size_t size);      // stereo_matcher
Outcome receiveDisparity(const uint8_t* data, size_t size);        // stixel, then snv_extrinsic
Outcome receiveStixels(const uint8_t* data, size_t size);          // snv_extrinsic, then validator
Outcome receiveSurfaceNormals(const uint8_t* data, size_t size);   // validator
Outcome receiveExtrinsics(const uint8_t* data, size_t size);       // stixel (ground prior)

}  // namespace nerv::fuzz
