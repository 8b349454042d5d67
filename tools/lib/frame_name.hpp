// A frame's name from its header.frame_id: the part after the last '/' ("kitti_raw_0926_seq/0000000005"
// -> "0000000005", as nerv_source sends "<folder>/<frame>"), the whole id when it has none. Label,
// ground-truth and pose files are named by it.
#pragma once

#include <string>

namespace nerv {

inline std::string frameName(const std::string& frame_id) { return frame_id.substr(frame_id.find_last_of('/') + 1); }

}  // namespace nerv
