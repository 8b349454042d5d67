// A Motion-JPEG AVI writer (RIFF AVI 1.0 with an idx1 index, one video
// stream), so `nerv_render --video` needs only imgcodecs: the tool library is
// not linked with OpenCV's videoio. Every player that opens OpenCV's MJPG
// output opens this. Files are limited to 1 GiB (no OpenDML extension).
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace nerv::viz {

class MjpegAviWriter {
 public:
  MjpegAviWriter() = default;
  ~MjpegAviWriter();
  MjpegAviWriter(const MjpegAviWriter&) = delete;
  MjpegAviWriter& operator=(const MjpegAviWriter&) = delete;

  // Returns false when the file cannot be created.
  bool open(const std::string& path, cv::Size frame_size, double fps, int jpeg_quality = 90);
  bool isOpened() const { return out_.is_open(); }
  // BGR 8-bit frames of the opened size. Returns false on a write error or a size mismatch.
  bool write(const cv::Mat& bgr);
  // Writes the index and the sizes; also done by the destructor.
  bool close();
  int frames() const { return static_cast<int>(index_.size()); }

 private:
  struct IndexEntry {
    uint32_t offset, size;
  };
  void writeHeaders();
  std::ofstream out_;
  cv::Size size_;
  double fps_ = 10;
  int quality_ = 90;
  std::vector<IndexEntry> index_;
  uint32_t max_frame_bytes_ = 0;
  std::streamoff movi_list_pos_ = 0;  // position of the 'movi' LIST size field
};

}  // namespace nerv::viz
