#include "log_frames.hpp"

#include <stdexcept>

namespace nerv {

LogFrameReader::LogFrameReader(const std::string& path, const LogFrameOptions& options)
    : options_(options), pipeline_(options.prefix) {
  log_ = std::make_unique<lcm::LogFile>(path, "r");
  if (!log_->good()) throw std::runtime_error("log " + path + " cannot be read");
}

LogFrameReader::~LogFrameReader() = default;

namespace {

template <class T>
struct Tag {
  using type = T;
};

bool complete(const LogFrame& f) {
  return f.stereo && f.disparity && f.stixels && f.normals && f.extrinsics && f.detections;
}

}  // namespace

void LogFrameReader::absorb(const lcm::LogEvent& e) {
  ++stats_.events;
  if (!pipeline_.take(e.channel)) {  // another camera's frames: their seqs are their own
    ++stats_.other_pipeline;
    return;
  }
  const int64_t fp = messageFingerprint(e.data, e.datalen);
  // Decodes into the frame's slot unless it is filled already. Returns false
  // when the fingerprint is not T's.
  auto take = [&](auto tag, auto member, auto after) -> bool {
    using T = typename decltype(tag)::type;
    if (fp != T::getHash()) return false;
    T msg;
    // Generated decoders can throw on a cut or corrupt buffer (a garbage array
    // length makes std::vector throw), not only return < 0.
    bool ok = false;
    try {
      ok = msg.decode(e.data, 0, e.datalen) >= 0;
    } catch (const std::exception&) {
      ok = false;
    }
    if (!ok) {
      ++stats_.broken;
      ++stats_.broken_per_channel[e.channel];
      return true;
    }
    ++stats_.frame_messages;
    const int64_t seq = msg.header.seq;
    if (seq < options_.seq_min || seq > options_.seq_max) return true;
    if (!options_.seqs.empty() && !options_.seqs.count(seq)) return true;
    if (handed_out_.count(seq)) {
      ++stats_.duplicates;
      return true;
    }
    LogFrame& f = pending_[seq];
    f.seq = seq;
    if (f.frame_id.empty()) f.frame_id = msg.header.frame_id;
    auto& slot = f.*member;
    if (slot) {
      ++stats_.duplicates;
      return true;
    }
    after(msg, f);
    slot = std::move(msg);
    return true;
  };
  auto nothing = [](auto&, LogFrame&) {};
  const bool keep = options_.keep_images;
  if (take(Tag<stereo_frame_t>{}, &LogFrame::stereo,
           [&](stereo_frame_t& m, LogFrame& f) {
             ++stats_.stereo_frames;
             f.stereo_log_utime = e.timestamp;
             if (!keep) {
               m.left.data.clear();
               m.right.data.clear();
             }
           }))
    return;
  if (take(Tag<disparity_t>{}, &LogFrame::disparity, [&](disparity_t& m, LogFrame&) {
        if (!keep) {
          m.data.clear();
          m.confidence.clear();
        }
      }))
    return;
  if (take(Tag<stixels_t>{}, &LogFrame::stixels, nothing)) return;
  if (take(Tag<surface_normals_t>{}, &LogFrame::normals, nothing)) return;
  if (take(Tag<extrinsics_t>{}, &LogFrame::extrinsics, nothing)) return;
  if (take(Tag<detections_t>{}, &LogFrame::detections,
           [&](detections_t&, LogFrame& f) { f.detections_log_utime = e.timestamp; }))
    return;
  ++stats_.other_messages;
}

bool LogFrameReader::popReady(LogFrame& frame, bool flush) {
  if (pending_.empty()) return false;
  auto oldest = pending_.begin();
  if (!flush && !complete(oldest->second) &&
      static_cast<int>(pending_.size()) <= options_.max_pending)
    return false;
  frame = std::move(oldest->second);
  handed_out_.insert(oldest->first);
  pending_.erase(oldest);
  return true;
}

bool LogFrameReader::next(LogFrame& frame) {
  while (!eof_) {
    if (popReady(frame, false)) return true;
    const lcm::LogEvent* e = log_->readNextEvent();
    if (!e) {
      eof_ = true;
      stats_.pipelines = pipeline_.note();  // (throws when the prefix asked for is not in the log)
      break;
    }
    absorb(*e);
  }
  return popReady(frame, true);
}

}  // namespace nerv
