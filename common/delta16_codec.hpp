// "delta16": a lossless, fast encoding of a uint16 disparity map for the wire,
// for links between computers where bytes count. At the Cityscapes preset's
// 2048x1024 the raw map (u16le) is 4.2 MB, and PNG (png16, 1.8 MB) takes 89 ms
// to encode and 39 ms to decode in every consumer; delta16 takes 2.45 MB in
// 5.6 / 6.0 ms (docs/stereo.md "Camera presets"). Here each value is coded as its difference to the pixel before it
// (the first pixel of a row: to the first pixel of the row above), zigzag-mapped
// to an unsigned number and written as a little-endian base-128 varint: 1 byte
// when the difference is within +-63 (1/4 px at the wire's 1/256 px: a surface),
// 2 within +-8191, 3 bytes at most (the jump from or to an invalid 0).
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace nerv {

// fixed: CV_16U. Replaces `out`'s contents (its capacity is kept).
void encodeDelta16(const cv::Mat& fixed, std::vector<uint8_t>& out);

// Decodes width x height values into `fixed` (CV_16U). Empty string on success;
// otherwise one line naming the problem (the stream ends early, a varint runs
// over 3 bytes, a value leaves 0..65535, bytes are left over) and `fixed` is
// not to be used. Never reads outside [data, data + size).
std::string decodeDelta16(const uint8_t* data, size_t size, int width, int height, cv::Mat& fixed);

// Bounds of a valid stream's size for width x height values [bytes].
inline size_t delta16MinBytes(int width, int height) { return static_cast<size_t>(width) * height; }
inline size_t delta16MaxBytes(int width, int height) { return 3 * static_cast<size_t>(width) * height; }

}  // namespace nerv
