#include "mjpeg_avi.hpp"

#include <opencv2/imgcodecs.hpp>

#include <cmath>

namespace nerv::viz {

namespace {

void put32(std::ofstream& o, uint32_t v) {
  const char b[4] = {char(v & 0xff), char((v >> 8) & 0xff), char((v >> 16) & 0xff), char((v >> 24) & 0xff)};
  o.write(b, 4);
}
void put16(std::ofstream& o, uint16_t v) {
  const char b[2] = {char(v & 0xff), char((v >> 8) & 0xff)};
  o.write(b, 2);
}
void fourcc(std::ofstream& o, const char* c) { o.write(c, 4); }

// Header positions patched by close(): fixed by the layout written in writeHeaders().
constexpr std::streamoff kRiffSizePos = 4;
constexpr std::streamoff kAvihTotalFramesPos = 12 + 12 + 8 + 16;
constexpr std::streamoff kAvihBufferPos = kAvihTotalFramesPos + 12;
constexpr std::streamoff kStrhLengthPos = 12 + 12 + 8 + 56 + 12 + 8 + 32;
constexpr std::streamoff kStrhBufferPos = kStrhLengthPos + 4;

}  // namespace

MjpegAviWriter::~MjpegAviWriter() { close(); }

bool MjpegAviWriter::open(const std::string& path, cv::Size frame_size, double fps, int jpeg_quality) {
  close();
  if (frame_size.width <= 0 || frame_size.height <= 0 || !(fps > 0)) return false;
  out_.open(path, std::ios::binary | std::ios::trunc);
  if (!out_) return false;
  size_ = frame_size;
  fps_ = fps;
  quality_ = jpeg_quality;
  index_.clear();
  max_frame_bytes_ = 0;
  writeHeaders();
  return static_cast<bool>(out_);
}

void MjpegAviWriter::writeHeaders() {
  const uint32_t w = size_.width, h = size_.height;
  // Frame rate as a rational rate/scale with a millisecond-ish precision.
  const uint32_t scale = 1000, rate = static_cast<uint32_t>(std::lround(fps_ * scale));
  fourcc(out_, "RIFF");
  put32(out_, 0);  // patched
  fourcc(out_, "AVI ");
  fourcc(out_, "LIST");
  put32(out_, 4 + (8 + 56) + (12 + (8 + 56) + (8 + 40)));
  fourcc(out_, "hdrl");
  fourcc(out_, "avih");
  put32(out_, 56);
  put32(out_, static_cast<uint32_t>(std::lround(1e6 / fps_)));  // microseconds per frame
  put32(out_, 0);      // max bytes per second
  put32(out_, 0);      // padding granularity
  put32(out_, 0x10);   // AVIF_HASINDEX
  put32(out_, 0);      // total frames (patched)
  put32(out_, 0);      // initial frames
  put32(out_, 1);      // streams
  put32(out_, 0);      // suggested buffer size (patched)
  put32(out_, w);
  put32(out_, h);
  for (int i = 0; i < 4; ++i) put32(out_, 0);
  fourcc(out_, "LIST");
  put32(out_, 4 + (8 + 56) + (8 + 40));
  fourcc(out_, "strl");
  fourcc(out_, "strh");
  put32(out_, 56);
  fourcc(out_, "vids");
  fourcc(out_, "MJPG");
  put32(out_, 0);           // flags
  put16(out_, 0);           // priority
  put16(out_, 0);           // language
  put32(out_, 0);           // initial frames
  put32(out_, scale);
  put32(out_, rate);
  put32(out_, 0);           // start
  put32(out_, 0);           // length in frames (patched)
  put32(out_, 0);           // suggested buffer size (patched)
  put32(out_, 0xffffffff);  // quality: default
  put32(out_, 0);           // sample size: varies
  put16(out_, 0);
  put16(out_, 0);
  put16(out_, static_cast<uint16_t>(w));
  put16(out_, static_cast<uint16_t>(h));
  fourcc(out_, "strf");
  put32(out_, 40);          // BITMAPINFOHEADER
  put32(out_, 40);
  put32(out_, w);
  put32(out_, h);
  put16(out_, 1);           // planes
  put16(out_, 24);          // bits per pixel
  fourcc(out_, "MJPG");
  put32(out_, w * h * 3);
  for (int i = 0; i < 4; ++i) put32(out_, 0);
  fourcc(out_, "LIST");
  movi_list_pos_ = out_.tellp();
  put32(out_, 0);           // patched
  fourcc(out_, "movi");
}

bool MjpegAviWriter::write(const cv::Mat& bgr) {
  if (!out_.is_open() || bgr.size() != size_ || bgr.type() != CV_8UC3) return false;
  std::vector<uint8_t> jpeg;
  if (!cv::imencode(".jpg", bgr, jpeg, {cv::IMWRITE_JPEG_QUALITY, quality_})) return false;
  const std::streamoff chunk = out_.tellp();
  fourcc(out_, "00dc");
  put32(out_, static_cast<uint32_t>(jpeg.size()));
  out_.write(reinterpret_cast<const char*>(jpeg.data()), static_cast<std::streamsize>(jpeg.size()));
  if (jpeg.size() % 2) out_.put(0);  // RIFF chunks are word aligned
  // idx1 offsets count from the 'movi' fourcc.
  index_.push_back({static_cast<uint32_t>(chunk - (movi_list_pos_ + 4)), static_cast<uint32_t>(jpeg.size())});
  max_frame_bytes_ = std::max<uint32_t>(max_frame_bytes_, static_cast<uint32_t>(jpeg.size()));
  return static_cast<bool>(out_);
}

bool MjpegAviWriter::close() {
  if (!out_.is_open()) return true;
  const std::streamoff movi_end = out_.tellp();
  fourcc(out_, "idx1");
  put32(out_, static_cast<uint32_t>(index_.size() * 16));
  for (const auto& e : index_) {
    fourcc(out_, "00dc");
    put32(out_, 0x10);  // AVIIF_KEYFRAME
    put32(out_, e.offset);
    put32(out_, e.size);
  }
  const std::streamoff end = out_.tellp();
  const uint32_t frames = static_cast<uint32_t>(index_.size());
  out_.seekp(kRiffSizePos);
  put32(out_, static_cast<uint32_t>(end - 8));
  out_.seekp(kAvihTotalFramesPos);
  put32(out_, frames);
  out_.seekp(kAvihBufferPos);
  put32(out_, max_frame_bytes_ + 8);
  out_.seekp(kStrhLengthPos);
  put32(out_, frames);
  out_.seekp(kStrhBufferPos);
  put32(out_, max_frame_bytes_ + 8);
  out_.seekp(movi_list_pos_);
  put32(out_, static_cast<uint32_t>(movi_end - movi_list_pos_ - 4));
  const bool ok = static_cast<bool>(out_);
  out_.close();
  return ok;
}

}  // namespace nerv::viz
