// Deterministic mutation test of every received message type: valid messages of
// a small scene, encoded as on the bus, get seeded mutations (bit flips, byte
// overwrites, truncation, length fields, NaN/inf/huge numbers and absurd sizes
// written into decoded fields and re-encoded). Each mutant goes the way the
// receiving service takes it (tests/fuzz/receive_paths.hpp): it is rejected with
// a named counter, or it is processed without an exception into outputs the next
// stage accepts. The libFuzzer harnesses in tests/fuzz/ run the same paths.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <new>
#include <random>

#include <opencv2/imgcodecs.hpp>

#include "receive_paths.hpp"
#include "stixel_estimator.hpp"

using namespace nerv;
using namespace nerv::fuzz;

// Largest single allocation since reset (operator new is replaced in this
// program; not under AddressSanitizer, which has its own).
static size_t g_largest_allocation = 0;
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define NERV_ASAN 1
#endif
#endif
#ifndef NERV_ASAN
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(size_t n) {
  if (n > g_largest_allocation) g_largest_allocation = n;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
#endif

namespace {

using Path = std::function<Outcome(const uint8_t*, size_t)>;
using Bytes = std::vector<uint8_t>;

const float kFloats[] = {std::numeric_limits<float>::quiet_NaN(),
                         std::numeric_limits<float>::infinity(),
                         -std::numeric_limits<float>::infinity(),
                         0.0f, -0.0f, -1.0f, 1e-40f, 1e-30f, 1e30f, -1e30f, FLT_MAX, 1e6f, 65535.0f};
const int32_t kInts[] = {0, -1, 1, 2, 3, INT32_MIN, INT32_MAX, 65535, 65536, 1 << 20, -65536, 4097};

template <class Engine>
float pickFloat(Engine& rng) { return kFloats[rng() % (sizeof kFloats / sizeof *kFloats)]; }
template <class Engine>
int32_t pickInt(Engine& rng) { return kInts[rng() % (sizeof kInts / sizeof *kInts)]; }

// Count and size fields are changed in the encoded bytes (the encoder itself
// trusts them): big-endian int32 at offset.
Bytes withInt32(Bytes b, size_t offset, int32_t value) {
  const uint32_t v = static_cast<uint32_t>(value);
  for (int i = 0; i < 4 && offset + i < b.size(); ++i) b[offset + i] = static_cast<uint8_t>(v >> (24 - 8 * i));
  return b;
}
constexpr size_t kHash = 8;  // fingerprint before every encoded message
size_t stringSize(const std::string& s) { return 4 + s.size() + 1; }

// Byte-level mutations of an encoded message.
Bytes mutateBytes(Bytes b, std::mt19937& rng) {
  if (b.empty()) return b;
  switch (rng() % 6) {
    case 0:  // bit flips
      for (int k = 1 + rng() % 4; k > 0; --k) b[rng() % b.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
      break;
    case 1:  // byte overwrites
      for (int k = 1 + rng() % 8; k > 0; --k) {
        static const uint8_t values[] = {0x00, 0xff, 0x7f, 0x80, 0x01};
        b[rng() % b.size()] = values[rng() % 5];
      }
      break;
    case 2:  // truncation
      b.resize(rng() % b.size());
      break;
    case 3: {  // a 32-bit big-endian field (lengths, sizes, counts) overwritten
      if (b.size() < 4) break;
      const size_t at = rng() % (b.size() - 3);
      const uint32_t v = static_cast<uint32_t>(pickInt(rng));
      for (int i = 0; i < 4; ++i) b[at + i] = static_cast<uint8_t>(v >> (24 - 8 * i));
      break;
    }
    case 4: {  // a 32-bit field bumped by +-1 (off-by-one lengths)
      if (b.size() < 4) break;
      const size_t at = rng() % (b.size() - 3);
      uint32_t v = 0;
      for (int i = 0; i < 4; ++i) v = (v << 8) | b[at + i];
      v += (rng() % 2) ? 1u : ~0u;
      for (int i = 0; i < 4; ++i) b[at + i] = static_cast<uint8_t>(v >> (24 - 8 * i));
      break;
    }
    default:  // a chunk duplicated in place (grows the message)
    {
      const size_t at = rng() % b.size(), n = std::min<size_t>(1 + rng() % 64, b.size() - at);
      b.insert(b.begin() + at, b.begin() + at, b.begin() + at + n);
    }
  }
  return b;
}

// Field-level mutations: decode, change one field or array, re-encode.
void mutateCalibration(stereo_calibration_t& c, std::mt19937& rng) {
  double* doubles[] = {&c.fx, &c.fy, &c.cx, &c.cy, &c.baseline_m, &c.left_K[0], &c.left_K[2],
                       &c.left_D[0], &c.right_K[4], &c.right_D[4], &c.R[1], &c.T[0]};
  switch (rng() % 4) {
    case 0: c.width = pickInt(rng); break;
    case 1: c.height = pickInt(rng); break;
    case 2: c.rectified = !c.rectified; break;
    default: *doubles[rng() % 12] = pickFloat(rng);
  }
}

// True: the size field is to be set to size_field in the encoded bytes.
// Another kind of PNG of the image's size: 16-bit gray, 16-bit BGR, BGR, BGRA.
void recodeAsOtherPng(image_t& im, std::mt19937& rng) {
  cv::Mat gray(im.height > 0 && im.height <= 4096 ? im.height : 8, im.width > 0 && im.width <= 4096 ? im.width : 8,
               CV_8U);
  cv::randu(gray, 0, 256);
  cv::Mat other;
  switch (rng() % 4) {
    case 0: gray.convertTo(other, CV_16U, 257); break;
    case 1: cv::merge(std::vector<cv::Mat>{gray, gray, gray}, other), other.convertTo(other, CV_16U); break;
    case 2: cv::merge(std::vector<cv::Mat>{gray, gray, gray}, other); break;
    default: cv::merge(std::vector<cv::Mat>{gray, gray, gray, gray}, other);
  }
  cv::imencode(".png", other, im.data);
  im.size = static_cast<int32_t>(im.data.size());
  im.encoding = "png";
}

bool mutateImage(image_t& im, std::mt19937& rng, int32_t& size_field) {
  switch (rng() % 8) {
    case 7: recodeAsOtherPng(im, rng); break;
    case 0: im.width = pickInt(rng); break;
    case 1: im.height = pickInt(rng); break;
    case 2: im.channels = pickInt(rng); break;
    case 3: {
      static const char* encodings[] = {"gray8", "bgr8", "png", "jpeg", "", "tiff"};
      im.encoding = encodings[rng() % 6];
      break;
    }
    case 4: size_field = pickInt(rng); return true;
    case 5: im.data.resize(rng() % (im.data.size() + 1)); im.size = static_cast<int32_t>(im.data.size()); break;
    default:  // corrupt pixels or the compressed stream, sizes kept
      for (int k = 1 + rng() % 16; k > 0 && !im.data.empty(); --k) im.data[rng() % im.data.size()] = rng();
  }
  return false;
}

// Offset of image_t's size field from the start of the image.
size_t imageSizeOffset(const image_t& im) { return 12 + stringSize(im.encoding); }

template <class T>
bool decodeMsg(T& msg, const Bytes& b) {
  try {
    return msg.decode(b.data(), 0, static_cast<int>(b.size())) >= 0;
  } catch (...) {
    return false;
  }
}

Bytes mutateStereoFrame(const Bytes& seed, std::mt19937& rng) {
  stereo_frame_t f;
  EXPECT_TRUE(decodeMsg(f, seed));
  int32_t size_field = 0;
  const size_t left_at = kHash + f.header._getEncodedSizeNoHash() + f.calib._getEncodedSizeNoHash();
  switch (rng() % 4) {
    case 0: mutateCalibration(f.calib, rng); break;
    case 1:
      if (mutateImage(f.left, rng, size_field)) return withInt32(encode(f), left_at + imageSizeOffset(f.left), size_field);
      break;
    case 2:
      if (mutateImage(f.right, rng, size_field))
        return withInt32(encode(f), left_at + f.left._getEncodedSizeNoHash() + imageSizeOffset(f.right), size_field);
      break;
    default:  // a consistent but absurd or different size everywhere
      f.calib.width = f.left.width = f.right.width = pickInt(rng);
  }
  return encode(f);
}

Bytes mutateDisparity(const Bytes& seed, std::mt19937& rng) {
  disparity_t d;
  EXPECT_TRUE(decodeMsg(d, seed));
  switch (rng() % 9) {
    case 0: mutateCalibration(d.calib, rng); break;
    case 1: d.width = pickInt(rng); break;
    case 2: d.height = pickInt(rng); break;
    case 3: d.scale = pickFloat(rng); break;
    case 4: {
      const char* encodings[] = {"png16", "u16le", "delta16"};
      d.encoding = encodings[rng() % 3];
      break;
    }
    case 5:
    case 6: {
      const size_t size_at = kHash + d.header._getEncodedSizeNoHash() + d.calib._getEncodedSizeNoHash() +
                             12 + stringSize(d.encoding);
      const size_t at = (rng() % 2) ? size_at : size_at + 4 + d.data.size();  // size or confidence_size
      return withInt32(encode(d), at, pickInt(rng));
    }
    case 7:  // disparity values: all large, or random
      for (size_t i = 0; i < d.data.size(); ++i)
        d.data[i] = (rng() % 2) ? 0xff : static_cast<uint8_t>(rng());
      break;
    default:  // consistent but different size everywhere
      d.calib.width = d.width = pickInt(rng);
      if (d.encoding == "u16le") {
        d.data.resize(std::max<int64_t>(0, std::min<int64_t>(int64_t{2} * d.width * d.height, 1 << 22)));
        d.size = static_cast<int32_t>(d.data.size());
      }
  }
  return encode(d);
}

void mutateGround(ground_model_t& g, std::mt19937& rng) {
  float* floats[] = {&g.vd_slope, &g.vd_intercept, &g.horizon_row, &g.pitch_deg, &g.roll_deg,
                     &g.height_m, &g.residual_px};
  switch (rng() % 3) {
    case 0: g.valid = !g.valid; break;
    case 1: g.inliers = pickInt(rng); break;
    default: *floats[rng() % 7] = pickFloat(rng);
  }
}

void mutateRoi(roi_t& r, std::mt19937& rng) {
  int32_t* ints[] = {&r.id, &r.x, &r.y, &r.w, &r.h, &r.num_stixels};
  float* floats[] = {&r.x_m,        &r.y_m,        &r.z_m,       &r.width_m,          &r.height_m,
                     &r.distance_m, &r.nearest_z_m, &r.disparity, &r.nearest_z_sigma_m};
  if (rng() % 2) *ints[rng() % 6] = pickInt(rng);
  else *floats[rng() % 9] = pickFloat(rng);
}

Bytes mutateStixels(const Bytes& seed, std::mt19937& rng) {
  stixels_t s;
  EXPECT_TRUE(decodeMsg(s, seed));
  switch (rng() % 6) {
    case 0: mutateGround(s.ground, rng); break;
    case 1:
    case 2: {
      const size_t stixels_at = kHash + s.header._getEncodedSizeNoHash() + s.ground._getEncodedSizeNoHash();
      size_t rois_at = stixels_at + 4;
      for (const auto& x : s.stixels) rois_at += x._getEncodedSizeNoHash();
      return withInt32(encode(s), (rng() % 2) ? stixels_at : rois_at, pickInt(rng));
    }
    case 3:
      if (!s.stixels.empty()) {
        stixel_t& x = s.stixels[rng() % s.stixels.size()];
        int32_t* ints[] = {&x.u, &x.width, &x.top_row, &x.bottom_row};
        float* floats[] = {&x.disparity, &x.depth_m, &x.base_x_m, &x.base_y_m, &x.base_z_m};
        if (rng() % 2) *ints[rng() % 4] = pickInt(rng);
        else *floats[rng() % 5] = pickFloat(rng);
      }
      break;
    case 4:  // an extra ROI copied from another (duplicate id)
      if (!s.rois.empty()) {
        s.rois.push_back(s.rois[rng() % s.rois.size()]);
        s.num_rois = static_cast<int32_t>(s.rois.size());
      }
      [[fallthrough]];
    default:
      for (int k = 1 + rng() % 3; k > 0 && !s.rois.empty(); --k) mutateRoi(s.rois[rng() % s.rois.size()], rng);
  }
  return encode(s);
}

Bytes mutateSurfaceNormals(const Bytes& seed, std::mt19937& rng) {
  surface_normals_t n;
  EXPECT_TRUE(decodeMsg(n, seed));
  if (rng() % 8 == 0) {
    return withInt32(encode(n), kHash + n.header._getEncodedSizeNoHash() + 20, pickInt(rng));
  } else if (!n.rois.empty()) {
    normal_stats_t& s = n.rois[rng() % n.rois.size()];
    int32_t* ints[] = {&s.roi_id, &s.num_samples, &s.num_normals};
    float* floats[] = {&s.density, &s.ground_fraction, &s.object_fraction, &s.error_fraction,
                       &s.normal_x, &s.normal_y, &s.normal_z, &s.pitch_deg, &s.yaw_deg,
                       &s.tilt_from_ground_deg};
    if (rng() % 3 == 0) *ints[rng() % 3] = pickInt(rng);
    else *floats[rng() % 10] = pickFloat(rng);
  }
  return encode(n);
}

Bytes mutateExtrinsics(const Bytes& seed, std::mt19937& rng) {
  extrinsics_t e;
  EXPECT_TRUE(decodeMsg(e, seed));
  float* floats[] = {&e.pitch_deg, &e.roll_deg, &e.height_m, &e.confidence, &e.entropy,
                     &e.instant_pitch_deg};
  switch (rng() % 4) {
    case 0: e.valid = !e.valid; break;
    case 1: {
      static const int64_t seqs[] = {INT64_MIN, INT64_MIN + 1, -1, 0, 6, 7, INT64_MAX, -23};
      e.header.seq = seqs[rng() % 8];
      break;
    }
    default: *floats[rng() % 6] = pickFloat(rng);
  }
  return encode(e);
}

struct Tally {
  int accepted = 0, rejected = 0;
  std::map<std::string, int> counters;
};

// Runs every seed and `mutants` mutants per seed through the path; every
// outcome must be a named rejection or a clean acceptance.
Tally fuzzType(const std::string& type, const Path& path,
               Bytes (*mutateFields)(const Bytes&, std::mt19937&), int mutants, uint32_t seed) {
  Tally t;
  std::mt19937 rng(seed);
  const std::vector<Bytes> seeds = seedMessages(type);
  EXPECT_FALSE(seeds.empty());
  auto run = [&](const Bytes& b, const std::string& what) {
    const Outcome o = path(b.data(), b.size());
    EXPECT_TRUE(o.bug.empty()) << type << " " << what << ": " << o.bug;
    if (!o.bug.empty() && std::getenv("NERV_FUZZ_SAVE")) {  // keep the input for a regression test
      const std::string path = std::string(std::getenv("NERV_FUZZ_SAVE")) + "/" + type + "_" + what.substr(what.rfind(' ') + 1);
      if (FILE* f = std::fopen(path.c_str(), "wb")) std::fwrite(b.data(), 1, b.size(), f), std::fclose(f);
    }
    EXPECT_TRUE(o.accepted || !o.counter.empty()) << type << " " << what;
    if (o.accepted) ++t.accepted;
    else ++t.rejected, ++t.counters[o.counter];
  };
  for (size_t s = 0; s < seeds.size(); ++s) {
    const Outcome o = path(seeds[s].data(), seeds[s].size());
    EXPECT_TRUE(o.accepted && o.bug.empty()) << type << " seed " << s << " is not accepted: "
                                             << o.counter << " " << o.message << o.bug;
    for (int i = 0; i < mutants; ++i) {
      // Half byte-level, half field-level; some field mutants get a byte mutation on top.
      Bytes b = (i % 2) ? mutateFields(seeds[s], rng) : mutateBytes(seeds[s], rng);
      if (i % 7 == 3) b = mutateBytes(b, rng);
      run(b, "seed " + std::to_string(s) + " mutant " + std::to_string(i));
    }
  }
  std::string summary;
  for (const auto& [c, n] : t.counters) summary += " " + c + "=" + std::to_string(n);
  std::printf("%s: %d accepted, %d rejected:%s\n", type.c_str(), t.accepted, t.rejected, summary.c_str());
  EXPECT_GT(t.accepted, 0) << type;
  EXPECT_GT(t.rejected, 0) << type;
  return t;
}

}  // namespace

TEST(commonMessageFuzz, StereoFrameMutants) {
  fuzzType("stereo_frame", receiveStereoFrame, mutateStereoFrame, 400, 1);
}

TEST(commonMessageFuzz, DisparityMutants) {
  fuzzType("disparity", receiveDisparity, mutateDisparity, 1000, 2);
}

TEST(commonMessageFuzz, StixelsMutants) {
  fuzzType("stixels", receiveStixels, mutateStixels, 2000, 3);
}

TEST(commonMessageFuzz, SurfaceNormalsMutants) {
  fuzzType("surface_normals", receiveSurfaceNormals, mutateSurfaceNormals, 3000, 4);
}

TEST(commonMessageFuzz, ExtrinsicsMutants) {
  fuzzType("extrinsics", receiveExtrinsics, mutateExtrinsics, 1000, 5);
}

// The scene really exercises the paths: ROIs for snv and the validator, a pose
// the stixel stage takes as its prior.
TEST(commonMessageFuzz, SceneHasRoisAndAValidPose) {
  const Scene& s = scene();
  EXPECT_GE(s.stixels.num_rois, 1);
  EXPECT_TRUE(s.stixels.ground.valid);
  EXPECT_EQ(s.normals.num_rois, s.stixels.num_rois);
  EXPECT_TRUE(s.extrinsics.valid) << s.extrinsics.status;
  EXPECT_GE(s.extrinsics.confidence, 0.3f);
  // The extrinsics path's disparity has too little road for a fit of its own.
  EXPECT_FALSE(stixel::estimateStixels(weakGroundDisparity(), s.camera, stixel::Params{}).ground.valid);
  stixel::GroundPrior prior{true, 1.0f, 0.0f, 1.65f};
  EXPECT_EQ(stixel::estimateStixels(weakGroundDisparity(), s.camera, stixel::Params{}, prior).ground.source,
            "extrinsics_prior");
}

// --- regressions: the minimal inputs of what the mutations found -------------

// lcm-gen's decoders resized arrays to the count on the wire before checking the
// bytes were there: a short message with a corrupt count allocated gigabytes
// (cmake/LcmDecoderBounds.cmake). Now it fails to decode without allocating.
TEST(commonMessageFuzz, CorruptArrayCountFailsToDecodeWithoutAllocating) {
  const Scene& s = scene();
  const size_t stixels_at = kHash + s.stixels.header._getEncodedSizeNoHash() +
                            s.stixels.ground._getEncodedSizeNoHash();
  const size_t normals_at = kHash + s.normals.header._getEncodedSizeNoHash() + 20;
  const size_t data_at = kHash + s.disparity_msg.header._getEncodedSizeNoHash() +
                         s.disparity_msg.calib._getEncodedSizeNoHash() + 12 +
                         stringSize(s.disparity_msg.encoding);
  for (int32_t count : {INT32_MAX, 1 << 24, -1, INT32_MIN}) {
    const Bytes stixels = withInt32(encode(s.stixels), stixels_at, count);
    const Bytes normals = withInt32(encode(s.normals), normals_at, count);
    const Bytes disparity = withInt32(encode(s.disparity_msg), data_at, count);
    stixels_t st;
    surface_normals_t sn;
    disparity_t di;
    g_largest_allocation = 0;
    EXPECT_LT(st.decode(stixels.data(), 0, static_cast<int>(stixels.size())), 0) << count;
    EXPECT_LT(sn.decode(normals.data(), 0, static_cast<int>(normals.size())), 0) << count;
    EXPECT_LT(di.decode(disparity.data(), 0, static_cast<int>(disparity.size())), 0) << count;
    EXPECT_LT(g_largest_allocation, disparity.size() + 1024) << count;
  }
  // A zero string length (no terminating NUL) is a failed decode too, not a throw.
  Bytes e = encode(s.extrinsics);
  e = withInt32(e, kHash + 16, 0);  // header_t.frame_id length
  extrinsics_t ex;
  EXPECT_LT(ex.decode(e.data(), 0, static_cast<int>(e.size())), 0);
}

// PriorSelection computed the age as seq - e.seq in int64: a pose whose header
// says seq INT64_MIN wrapped to a negative age and became every later frame's prior.
TEST(commonMessageFuzz, PoseWithAFarSeqIsNoPrior) {
  extrinsics_t e = scene().extrinsics;
  e.valid = true;
  e.confidence = 0.9f;
  e.pitch_deg = 1.0f;
  e.height_m = 1.65f;
  for (int64_t seq : {INT64_MIN, INT64_MIN + 1, int64_t{-23}}) {
    e.header.seq = seq;
    const Bytes b = encode(e);
    const Outcome o = receiveExtrinsics(b.data(), b.size());
    EXPECT_TRUE(o.accepted) << seq;
    EXPECT_EQ(o.bug, "") << seq;
  }
}
// A 16-bit (or otherwise non-8-bit) PNG passed decodeImage and made the matcher
// throw (counted as processing_failed): now it is a bad_image.
TEST(commonMessageFuzz, SixteenBitPngFrameIsBadImage) {
  const Scene& s = scene();
  stereo_frame_t f = s.frame;
  cv::Mat wide;
  s.left.convertTo(wide, CV_16U, 257);
  f.left.encoding = f.right.encoding = "png";
  cv::imencode(".png", wide, f.left.data);
  f.right.data = f.left.data;
  f.left.size = f.right.size = static_cast<int32_t>(f.left.data.size());
  const Bytes b = encode(f);
  const Outcome o = receiveStereoFrame(b.data(), b.size());
  EXPECT_EQ(o.counter, "bad_image");
  EXPECT_EQ(o.bug, "");
}

// cv::imdecode throws on an empty buffer: an empty png/png16 stream reached it.
TEST(commonMessageFuzz, EmptyCompressedStreamIsRejectedNotThrown) {
  const Scene& s = scene();
  stereo_frame_t f = s.frame;
  f.left.encoding = "png";
  f.left.data.clear();
  f.left.size = 0;
  Bytes b = encode(f);
  Outcome o = receiveStereoFrame(b.data(), b.size());
  EXPECT_EQ(o.counter, "bad_image");
  EXPECT_EQ(o.bug, "");
  disparity_t d = s.disparity_msg;
  d.encoding = "png16";
  d.data.clear();
  d.size = 0;
  b = encode(d);
  o = receiveDisparity(b.data(), b.size());
  EXPECT_EQ(o.counter, "bad_disparity");
  EXPECT_EQ(o.bug, "");
}

// A finite but absurd principal point (a flipped exponent bit: cx = -2.6e305)
// passed the check and the stixel stage published an infinite foot point.
TEST(commonMessageFuzz, AbsurdCalibrationIsBadCalibration) {
  const Scene& s = scene();
  for (auto mutate : std::vector<std::function<void(stereo_calibration_t&)>>{
           [](stereo_calibration_t& c) { c.cx = -2.63334e305; },
           [](stereo_calibration_t& c) { c.cy = 1e30; },
           [](stereo_calibration_t& c) { c.fx = c.fy = 1e300; },
           [](stereo_calibration_t& c) { c.baseline_m = 1e300; }}) {
    disparity_t d = s.disparity_msg;
    mutate(d.calib);
    Bytes b = encode(d);
    Outcome o = receiveDisparity(b.data(), b.size());
    EXPECT_EQ(o.counter, "bad_calibration") << o.message;
    EXPECT_EQ(o.bug, "");
    stereo_frame_t f = s.frame;
    mutate(f.calib);
    b = encode(f);
    o = receiveStereoFrame(b.data(), b.size());
    EXPECT_EQ(o.counter, "bad_calibration") << o.message;
    EXPECT_EQ(o.bug, "");
  }
}

// A raw calibration that passes RawStereoCalibration::problem() but that OpenCV
// cannot rectify (the baseline's square underflows: stereoRectify asserted) or
// whose rectified camera is unusable (huge distortion) was processed and threw,
// or published a DISPARITY with a NaN focal length.
TEST(commonMessageFuzz, UnrectifiableRawCalibrationIsBadCalibration) {
  const std::vector<Bytes> seeds = seedMessages("stereo_frame");
  stereo_frame_t raw;
  ASSERT_GE(raw.decode(seeds[3].data(), 0, static_cast<int>(seeds[3].size())), 0);
  ASSERT_FALSE(raw.calib.rectified);
  for (auto mutate : std::vector<std::function<void(stereo_calibration_t&)>>{
           [](stereo_calibration_t& c) { c.T[0] = -1e-200; },
           [](stereo_calibration_t& c) { c.left_D[0] = 1e30f; },
           [](stereo_calibration_t& c) { c.right_K[4] = 1e30; }}) {
    stereo_frame_t f = raw;
    mutate(f.calib);
    const Bytes b = encode(f);
    const Outcome o = receiveStereoFrame(b.data(), b.size());
    EXPECT_EQ(o.counter, "bad_calibration") << o.message;
    EXPECT_EQ(o.bug, "");
  }
}

// Finite but impossible values that decided an answer downstream.
TEST(commonMessageFuzz, ImpossibleSharesBoxesAndConfidenceAreBadValue) {
  const Scene& s = scene();
  ASSERT_FALSE(s.normals.rois.empty());
  // A ground share of 1e30 reached the validator (it reads as all ground).
  surface_normals_t n = s.normals;
  n.rois[0].ground_fraction = 1e30f;
  Bytes b = encode(n);
  Outcome o = receiveSurfaceNormals(b.data(), b.size());
  EXPECT_EQ(o.counter, "bad_value");
  n = s.normals;
  n.rois[0].num_normals = n.rois[0].num_samples + 1;
  b = encode(n);
  EXPECT_EQ(receiveSurfaceNormals(b.data(), b.size()).counter, "bad_value");
  // A box outside every accepted image was kept as an unvalidated detection.
  stixels_t st = s.stixels;
  st.rois[0].x = INT32_MAX - 5;
  b = encode(st);
  EXPECT_EQ(receiveStixels(b.data(), b.size()).counter, "bad_value");
  st.rois[0].x = -100;
  b = encode(st);
  EXPECT_EQ(receiveStixels(b.data(), b.size()).counter, "bad_value");
  // A NaN confidence passed "confidence < min_prior_confidence" and became the prior.
  extrinsics_t e = s.extrinsics;
  e.confidence = std::numeric_limits<float>::quiet_NaN();
  b = encode(e);
  EXPECT_EQ(receiveExtrinsics(b.data(), b.size()).counter, "bad_value");
}

// snv's groundRows cast the row where the STIXELS ground model reaches 30 m to
// int before clamping it: a tiny slope put it at -1.3e42 (undefined behaviour,
// found by fuzz_stixels under UBSan; this input traps there without the fix).
TEST(commonMessageFuzz, GroundModelFarOutsideTheImageIsClamped) {
  stixels_t st = scene().stixels;
  st.ground.valid = true;
  st.ground.vd_slope = 1e-30f;
  st.ground.vd_intercept = 1e12f;
  const Bytes b = encode(st);
  const Outcome o = receiveStixels(b.data(), b.size());
  EXPECT_TRUE(o.accepted);
  EXPECT_EQ(o.bug, "");
}

// A compressed stream was decoded before its size was compared with the message's:
// a few kB of PNG declaring 4096x4096 decoded to 16 MB first (up to 2^30 pixels
// pass OpenCV's own limit). Now the declared size is read from the header first.
TEST(commonMessageFuzz, CompressedStreamDeclaringAnotherSizeIsRejectedBeforeDecoding) {
  const Scene& s = scene();
  const cv::Mat big(4096, 4096, CV_8U, cv::Scalar(0));
  stereo_frame_t f = s.frame;
  f.left = encodeImage(big, "png");
  f.left.width = s.camera.width;
  f.left.height = s.camera.height;
  cv::Mat out;
  EXPECT_EQ(decodeImage(f.left, out), "png stream declares 4096x4096, header says 192x96");
  f.left = encodeImage(big, "jpeg");
  f.left.width = s.camera.width;
  f.left.height = s.camera.height;
  EXPECT_EQ(decodeImage(f.left, out), "jpeg stream declares 4096x4096, header says 192x96");
  const Bytes b = encode(f);
  EXPECT_EQ(receiveStereoFrame(b.data(), b.size()).counter, "bad_image");
  disparity_t d = s.disparity_msg;
  encodeDisparity(cv::Mat(4096, 4096, CV_32F, cv::Scalar(0)), "png16", d);
  d.width = s.camera.width;
  d.height = s.camera.height;
  EXPECT_EQ(decodeDisparity(d, out), "png16 stream declares 4096x4096, header says 192x96");
  // The real streams declare their own size.
  EXPECT_EQ(decodeImage(encodeImage(s.left, "png"), out), "");
  EXPECT_EQ(decodeImage(encodeImage(s.left, "jpeg"), out), "");
}
