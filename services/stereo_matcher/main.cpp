// stereo_matcher service: STEREO_FRAME -> DISPARITY.
#include <opencv2/imgproc.hpp>

#include <chrono>

#include "message_convert.hpp"
#include "service_config.hpp"
#include "stereo_matcher.hpp"

using namespace nerv;

namespace {

cv::Mat toGray(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

int serve(ServiceConfig& config) {
  const stereo::Params params = stereo::readParams(config.section());
  std::string encoding = "u16le";
  config.section().get("output_encoding", encoding, {"u16le", "png16"});
  int queue = 2;
  config.section().get("queue", queue, 1, 100);
  config.finish();

  Node node(config.nodeOptions());
  auto matcher = stereo::StereoMatcher::create(params);
  cv::Mat left, right, disparity;

  node.subscribe<stereo_frame_t>("STEREO_FRAME", [&](const stereo_frame_t& frame) {
    if (!node.ownsFrame(frame.header.seq)) return;  // another shard's frame
    if (Problem p = checkStereoFrame(frame, node.options().limits))
      return node.error(p.counter, "frame " + std::to_string(frame.header.seq) + ": " + p.message);
    if (!frame.calib.rectified)
      return node.error("unrectified", "frame " + std::to_string(frame.header.seq) +
                                           ": unrectified pairs are not supported yet");
    std::string why = decodeImage(frame.left, left);
    if (why.empty()) why = decodeImage(frame.right, right);
    if (!why.empty())
      return node.error("bad_image", "frame " + std::to_string(frame.header.seq) + ": " + why);
    node.countIn();

    const auto start = std::chrono::steady_clock::now();
    matcher->compute(toGray(left), toGray(right), disparity);
    disparity_t out;
    out.header = frame.header;
    out.calib = frame.calib;
    encodeDisparity(disparity, encoding, out);
    encodeConfidence(cv::Mat(), out);
    out.algorithm = matcher->name();
    out.min_disparity = static_cast<float>(params.min_disparity);
    out.max_disparity = static_cast<float>(params.min_disparity + params.num_disparities);
    out.processing_ms = std::chrono::duration<float, std::milli>(
                            std::chrono::steady_clock::now() - start).count();
    node.publish("DISPARITY", out);
    node.countOut(frame.header.utime, out.processing_ms);
  }, queue);
  return node.spin();
}

}  // namespace

int main(int argc, char** argv) { return runService("stereo_matcher", argc, argv, serve); }
