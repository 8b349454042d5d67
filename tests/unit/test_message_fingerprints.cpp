// Fingerprints that recorded drives depend on. `nerv replay` re-runs an older log through the
// current build from its STEREO_FRAME alone, whose layout is unchanged since the first commit:
// changing stereo_frame_t (or header_t, image_t, stereo_calibration_t inside it) makes every
// recorded drive unreplayable unless its old layout is kept for reading, as health_t's are
// (health_v1_t, health_v2_t: their fingerprints must stay those of the NERV_HEALTH that older
// builds published and older logs hold: health_v1_t's is that of a log recorded on 2026-12-05,
// health_v2_t's that of health_t.lcm at 9bb7c6e^).
#include <gtest/gtest.h>

#include <cstdint>

#include "nerv/health_t.hpp"
#include "nerv/health_v1_t.hpp"
#include "nerv/health_v2_t.hpp"
#include "nerv/stereo_frame_t.hpp"

namespace nerv {
namespace {

TEST(messageFingerprints, RecordedDrivesStayReplayable) {
  EXPECT_EQ(static_cast<uint64_t>(stereo_frame_t::getHash()), 0x9e3cbd4a7d729591ULL)
      << "stereo_frame_t changed layout: older logs no longer replay; keep the old one for reading";
}

TEST(messageFingerprints, OlderHealthLayoutsKeepTheirFingerprints) {
  EXPECT_EQ(static_cast<uint64_t>(health_v1_t::getHash()), 0x5e05c39e0f36adabULL);
  EXPECT_EQ(static_cast<uint64_t>(health_v2_t::getHash()), 0x9eda43cf9fa1d067ULL);
  EXPECT_NE(health_t::getHash(), health_v1_t::getHash());
  EXPECT_NE(health_t::getHash(), health_v2_t::getHash());
}

}  // namespace
}  // namespace nerv
