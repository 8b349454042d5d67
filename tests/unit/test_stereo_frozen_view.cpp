// Has one camera stopped (services/stereo_matcher/frozen_view.hpp)?
#include <gtest/gtest.h>

#include "frozen_view.hpp"

namespace nerv::stereo {
namespace {

cv::Mat frame(int seed, int width = 64, int height = 32) {
  cv::Mat m(height, width, CV_8UC1);
  cv::RNG(seed).fill(m, cv::RNG::UNIFORM, 0, 256);
  return m;
}

TEST(stereoFrozenView, DigestSeesEveryPixelAndTheSize) {
  const cv::Mat a = frame(1);
  cv::Mat b = a.clone();
  EXPECT_EQ(imageDigest(a), imageDigest(b));
  b.at<uchar>(31, 63) ^= 1;  // the last pixel, in the tail after the 8-byte words
  EXPECT_NE(imageDigest(a), imageDigest(b));
  b = a.clone();
  b.at<uchar>(0, 0) ^= 1;
  EXPECT_NE(imageDigest(a), imageDigest(b));
  // A region of interest is read by rows, not past them; the same bytes in another shape differ.
  const cv::Mat big = frame(2, 80, 40);
  EXPECT_EQ(imageDigest(big(cv::Rect(5, 3, 61, 20))), imageDigest(big(cv::Rect(5, 3, 61, 20)).clone()));
  EXPECT_NE(imageDigest(a.reshape(1, 64)), imageDigest(a));
  EXPECT_NE(imageDigest(cv::Mat()), imageDigest(frame(3)));
}

TEST(stereoFrozenView, OneViewRepeatingWhileTheOtherChanges) {
  FrozenViewCheck check(3);
  const cv::Mat stuck = frame(100);
  EXPECT_EQ(check.push(frame(1), stuck), "");   // first pair: nothing to compare with
  EXPECT_EQ(check.push(frame(2), stuck), "");   // 1 pair with the right repeated
  EXPECT_EQ(check.push(frame(3), stuck), "");   // 2
  EXPECT_EQ(check.push(frame(4), stuck), "right");  // 3: said
  EXPECT_EQ(check.framesStopped(), 3);
  EXPECT_EQ(check.push(frame(5), stuck), "right");
  EXPECT_EQ(check.framesStopped(), 4);
  // It moves again: the run ends.
  EXPECT_EQ(check.push(frame(6), frame(200)), "");
  EXPECT_EQ(check.framesStopped(), 0);
  // The left one stops.
  const cv::Mat left = frame(7);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(check.push(left, frame(300 + i)), "") << i;
  EXPECT_EQ(check.push(left, frame(310)), "left");
}

TEST(stereoFrozenView, AStillPairSentAgainIsNotAStoppedCamera) {
  FrozenViewCheck check(2);
  const cv::Mat l = frame(1), r = frame(2);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(check.push(l, r), "") << i;  // a replayed still frame
  EXPECT_EQ(check.framesStopped(), 0);
  // A single repeat of one view (a driver that sent one frame twice) is below the limit.
  FrozenViewCheck once(3);
  once.push(frame(1), frame(50));
  EXPECT_EQ(once.push(frame(2), frame(50)), "");
  EXPECT_EQ(once.push(frame(3), frame(51)), "");
  EXPECT_EQ(once.framesStopped(), 0);
  // Alternating which view repeats does not add up to a stopped camera.
  FrozenViewCheck alternating(2);
  const cv::Mat a = frame(60), b = frame(61);
  alternating.push(frame(1), a);
  EXPECT_EQ(alternating.push(frame(2), a), "");   // right repeated
  EXPECT_EQ(alternating.push(frame(2), b), "");   // left repeated: a new run
  EXPECT_EQ(alternating.framesStopped(), 1);
}

}  // namespace
}  // namespace nerv::stereo
