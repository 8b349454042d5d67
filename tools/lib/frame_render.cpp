#include "frame_render.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "frame_name.hpp"
#include "kitti_labels.hpp"
#include "mjpeg_avi.hpp"

namespace nerv::viz {

std::string labelFileFor(const std::string& labels_dir, const std::string& frame_id) {
  if (labels_dir.empty() || frame_id.empty()) return {};
  const std::string path = labels_dir + "/" + frameName(frame_id) + ".txt";
  return std::filesystem::exists(path) ? path : std::string();
}

RenderResult renderLog(const std::string& log_path, const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!std::filesystem::exists(log_path)) throw std::runtime_error("log " + log_path + " does not exist");
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (!std::filesystem::is_directory(options.out_dir))
    throw std::runtime_error("cannot make output folder " + options.out_dir);

  LogFrameOptions read;
  read.seq_min = options.seq_min;
  read.seq_max = options.seq_max;
  read.prefix = options.prefix;
  LogFrameReader reader(log_path, read);
  RenderResult result;
  MjpegAviWriter video;
  cv::Size video_size;
  LogFrame frame;
  while (reader.next(frame)) {
    std::vector<KittiLabel> labels;
    bool have_labels = false;
    if (const std::string path = labelFileFor(options.labels_dir, frame.frame_id); !path.empty()) {
      try {
        labels = readKittiLabels(path);
        have_labels = true;
      } catch (const std::exception&) {
        ++result.label_problems;
      }
    }
    GridOptions grid_options;
    grid_options.needles = options.needles;
    grid_options.labels = have_labels ? &labels : nullptr;
    std::string problem;
    cv::Mat grid = renderFrameGrid(frame, grid_options, &problem);
    if (grid.empty()) {
      ++result.skipped;
      if (result.first_problem.empty())
        result.first_problem = cv::format("seq %lld: ", static_cast<long long>(frame.seq)) + problem;
      continue;
    }
    if (options.scale > 0 && options.scale != 1.0)
      cv::resize(grid, grid, {}, options.scale, options.scale, cv::INTER_AREA);
    const std::string png = options.out_dir + "/" + cv::format("%06lld.png", static_cast<long long>(frame.seq));
    if (!cv::imwrite(png, grid)) throw std::runtime_error("cannot write " + png);
    ++result.rendered;
    if (options.video) {
      if (!video.isOpened()) {
        video_size = grid.size();
        result.video_path = options.out_dir + "/render.avi";
        if (!video.open(result.video_path, video_size, options.video_fps)) throw std::runtime_error("cannot open video " + result.video_path + " (MJPG)");
      }
      if (grid.size() != video_size) cv::resize(grid, grid, video_size);
      if (!video.write(grid)) throw std::runtime_error("cannot write video " + result.video_path);
    }
  }
  if (video.isOpened() && !video.close()) throw std::runtime_error("cannot finish video " + result.video_path);
  result.log = reader.stats();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace nerv::viz
