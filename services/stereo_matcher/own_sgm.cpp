#include "own_sgm.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "census_transform.hpp"
#include "cost_volume.hpp"
#include "lr_check.hpp"
#include "median_fill.hpp"
#include "path_aggregation.hpp"
#include "speckle_filter.hpp"
#include "streaming_store.hpp"
#include "winner_subpixel.hpp"

namespace nerv::stereo {
namespace {

// Runs body(i) for i in [0, n), in parallel on OpenCV's thread pool (kept
// alive between frames, unlike threads started per pass).
template <class F>
void runOnThreads(int n, F&& body) {
  if (n <= 1) {
    body(0);
    return;
  }
  cv::parallel_for_(cv::Range(0, n), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i) body(i);
  }, n);
}

// Runs body(task, worker) for every task in [0, tasks) on up to `threads`
// threads that pull tasks from a shared counter: on a computer shared with
// other processes a slowed thread simply takes fewer tasks.
template <class F>
void parallelTasks(int threads, int tasks, F&& body) {
  std::atomic<int> next{0};
  runOnThreads(std::max(1, std::min(threads, tasks)), [&](int worker) {
    for (int task; (task = next.fetch_add(1)) < tasks;) body(task, worker);
  });
}

// Marks the outer `border_x` columns, `top` rows and `bottom` rows invalid.
void invalidateBorder(cv::Mat& disparity, cv::Mat& confidence, int border_x, int top, int bottom) {
  const int rows = disparity.rows, cols = disparity.cols;
  const int bx = std::min(std::max(border_x, 0), cols);
  for (int y = 0; y < rows; ++y) {
    float* d = disparity.ptr<float>(y);
    float* c = confidence.ptr<float>(y);
    if (y < top || y >= rows - bottom) {  // whole row
      std::fill(d, d + cols, 0.0f);
      std::fill(c, c + cols, 0.0f);
      continue;
    }
    std::fill(d, d + bx, 0.0f);  // only the side columns
    std::fill(c, c + bx, 0.0f);
    std::fill(d + cols - bx, d + cols, 0.0f);
    std::fill(c + cols - bx, c + cols, 0.0f);
  }
}

// A left pixel whose census code is 0 sees no texture at all: every pair in its
// window compares equal (a saturated patch of glare or sky, a clipped shadow). Its
// cost at disparity d is then the popcount of the right code alone, so the winner
// is wherever the right view is flattest - for the same glare in both lenses, the
// glare's own edges at disparity ~0 (docs/stixel.md "Free or unseen"). No
// measurement there, so no disparity.
void invalidateFlatCensus(const cv::Mat& left, const cv::Mat& census_left, cv::Mat& disparity, cv::Mat& confidence) {
  for (int y = 0; y < disparity.rows; ++y) {
    const uint32_t* c = census_left.ptr<uint32_t>(y);
    const uint8_t* g = left.ptr<uint8_t>(y);
    float* d = disparity.ptr<float>(y);
    float* q = confidence.ptr<float>(y);
    for (int x = 0; x < disparity.cols; ++x)
      if (c[x] == 0 && g[x] >= 250) d[x] = 0.0f, q[x] = 0.0f;
  }
}

struct StripeWorkspace {
  std::vector<uint8_t> forward, backward, vertical[2], vertical_min[2];
  // one segment of pass 3: its rows' costs and the first vertical path's rows
  std::vector<uint8_t> segment_costs, segment_paths, segment_min[2];
  std::vector<uint8_t> sum, right_cost;
  std::vector<int16_t> best_left, best_right, right_index;
};

// A vertical path's L row (cols * D) and per-pixel minima where it left its half.
struct PathEdge {
  std::vector<uint8_t> row, min;
};

// The first vertical path of a half (pass 2) at every k-th row: the rows
// pass 3 restarts it from. Row j (cols * D bytes) and its minima (cols) are
// the path's L at path index (j + 1) * k - 1, the row before segment j + 1.
struct PathCheckpoints {
  AlignedBytes rows;
  std::vector<uint8_t> min;
};

class OwnSgm : public StereoMatcher {
 public:
  OwnSgm(const Params& p, bool simd, int segment_rows)
      : p_(p), simd_(simd && pathSimdAvailable()), segment_rows_(segment_rows) {
    CV_Assert(segment_rows_ >= 1);
    checkParams(p_);
    pen_.p1 = p.sgm_p1;
    pen_.p2 = p.sgm_p2;
  }

  std::string name() const override { return "nerv_sgm"; }

  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity,
               cv::Mat& confidence) override {
    CV_Assert(left.type() == CV_8UC1 && right.type() == CV_8UC1 && left.size() == right.size());
    const int rows = left.rows, cols = left.cols, D = p_.num_disparities;
    const int threads = std::max(1, std::min(p_.threads, rows));
    const size_t row_bytes = static_cast<size_t>(cols) * D;
    const int h = rows / 2;
    const int k = segment_rows_;
    // Path index i runs along a half's first vertical path (pass 2): top-down
    // in the upper half (row i), bottom-up in the lower (row rows - 1 - i).
    const int half_rows[2] = {h, rows - h};
    auto row_of = [&](int half, int i) { return half == 0 ? i : rows - 1 - i; };
    for (int half = 0; half < 2; ++half) {
      const int n = std::max(half_rows[half] - 1, 0) / k;  // segments after the first one
      checkpoints_[half].rows.resize(row_bytes * n);
      checkpoints_[half].min.resize(static_cast<size_t>(cols) * n);
    }
    for (PathEdge* edge : {&down_edge_, &up_edge_}) {
      edge->row.resize(row_bytes);
      edge->min.resize(cols);
    }
    workspaces_.resize(threads);
    census_left_.create(left.size(), CV_32SC1);
    census_right_.create(left.size(), CV_32SC1);
    right_reversed_.create(rows, cols + p_.min_disparity + D, CV_32SC1);
    disparity.create(left.size(), CV_32FC1);
    confidence.create(left.size(), CV_32FC1);

#ifdef NERV_SGM_PROFILE
    auto t_prev = std::chrono::steady_clock::now();
#define PROFILE_MARK(what) { auto t_now = std::chrono::steady_clock::now(); std::fprintf(stderr, "%s %.1f ms  ", what, std::chrono::duration<double, std::milli>(t_now - t_prev).count()); t_prev = t_now; }
#else
#define PROFILE_MARK(what)
#endif
    constexpr int kRowsPerTask = 8;
    const int road_row = roadCensusRow(p_, rows);
    const int row_tasks = (rows + kRowsPerTask - 1) / kRowsPerTask;
    // 1. census of both views
    parallelTasks(threads, row_tasks, [&](int task, int) {
      const int begin = task * kRowsPerTask, end = std::min(rows, begin + kRowsPerTask);
      const int mid = std::clamp(road_row, begin, end);  // [begin, mid): main window, [mid, end): road band
      if (mid > begin) {
        censusTransform(left, p_.census_width, p_.census_height, census_left_, begin, mid);
        censusTransform(right, p_.census_width, p_.census_height, census_right_, begin, mid);
      }
      if (end > mid) {
        censusTransform(left, p_.road_census_width, p_.road_census_height, census_left_, mid, end);
        censusTransform(right, p_.road_census_width, p_.road_census_height, census_right_, mid, end);
      }
      for (int y = begin; y < end; ++y)
        reverseCensusRow(census_right_.ptr<uint32_t>(y), cols, p_.min_disparity, D,
                         right_reversed_.ptr<uint32_t>(y));
    });
    PROFILE_MARK("census");
    // 2. vertical paths, each over half of the rows (split at h): top-down over
    // [0, h), bottom-up over [h, rows); of each only every k-th row is kept
    // (streamed to the checkpoints), where pass 3 recomputes it from, and its
    // last row (top-down at h - 1, bottom-up at h), where pass 3 continues it
    // over the other half. Columns are independent along vertical paths, so
    // each (direction, column band) is a task.
    constexpr int kColumnBands = 8;
    parallelTasks(threads, 2 * kColumnBands, [&](int task, int) {
      const bool downward = task % 2 == 0;
      const int band = task / 2;
      const int x0 = cols * band / kColumnBands, x1 = cols * (band + 1) / kColumnBands;
      const int n = x1 - x0;
      const int half = downward ? 0 : 1;
      const int path_rows = half_rows[half];
      if (n <= 0 || path_rows <= 0) return;
      PathCheckpoints& kept = checkpoints_[half];
      // The path runs in two cache-resident row buffers; every k-th finished
      // row is streamed to the checkpoints that pass 3 reads.
      std::vector<uint8_t> mins_a(n), mins_b(n), row_a(static_cast<size_t>(n) * D),
          row_b(static_cast<size_t>(n) * D), costs(static_cast<size_t>(n) * D);
      uint8_t* prev_min = mins_a.data();
      uint8_t* out_min = mins_b.data();
      uint8_t* prev_row = row_a.data();
      uint8_t* out_row = row_b.data();
      const size_t x_offset = static_cast<size_t>(x0) * D;
      for (int i = 0; i < path_rows; ++i) {
        const int y = row_of(half, i);
        censusCostRange(census_left_.ptr<uint32_t>(y), right_reversed_.ptr<uint32_t>(y), cols, x0,
                        x1, p_.min_disparity, D, costs.data());
        const int checkpoint = (i + 1) % k == 0 && i + 1 < path_rows ? (i + 1) / k - 1 : -1;
        aggregateRowVertical(costs.data(), i == 0 ? nullptr : prev_row, prev_min, n, D, pen_, simd_,
                             out_row, out_min,
                             checkpoint < 0 ? nullptr : kept.rows.data() + row_bytes * checkpoint + x_offset);
        if (checkpoint >= 0)
          std::copy(out_min, out_min + n, kept.min.begin() + static_cast<size_t>(cols) * checkpoint + x0);
        std::swap(prev_min, out_min);
        std::swap(prev_row, out_row);
      }
      PathEdge& edge = downward ? down_edge_ : up_edge_;
      std::copy(prev_row, prev_row + static_cast<size_t>(n) * D, edge.row.begin() + x_offset);
      std::copy(prev_min, prev_min + n, edge.min.begin() + x0);
      streamingFence();
    });
    PROFILE_MARK("vertical");
    // 3. per half, in segments of k rows walked in the direction of the
    // continued path (the upper half from h - 1 up to row 0, the lower from h
    // down): first the half's own vertical path is recomputed over the
    // segment from the checkpoint before it, in its own direction, keeping
    // its rows and their costs (2 * k rows, in L2 and L3); then per row,
    // from the segment's far end back, the other vertical path continued from
    // the edge (in a cache-resident row), the horizontal paths on the kept
    // costs, the average of the four, winners for the left and right views
    // and the left-right check. Costs are computed twice per pixel (pass 2 and
    // here), the first path twice as well, and no volume goes through memory.
    // A path is sequential in rows, so the tasks are the two halves. One row
    // at a time: two rows with interleaved horizontal paths (four chains)
    // measured no faster here.
    WinnerOptions options;
    options.uniqueness_ratio = p_.uniqueness_ratio;
    options.subpixel = p_.subpixel;
    parallelTasks(threads, 2, [&](int half, int worker) {
      const bool top = half == 0;
      const int n = half_rows[half];
      if (n <= 0) return;
      StripeWorkspace& w = workspaces_[worker];
      w.segment_costs.resize(row_bytes * std::min(k, n));
      w.segment_paths.resize(row_bytes * std::min(k, n));
      w.forward.resize(row_bytes);
      w.backward.resize(row_bytes);
      for (int j = 0; j < 2; ++j) {
        w.vertical[j].resize(row_bytes);
        w.vertical_min[j].resize(cols);
        w.segment_min[j].resize(cols);
      }
      w.sum.resize(row_bytes);
      w.best_left.resize(cols);
      w.best_right.resize(cols);
      const PathCheckpoints& kept = checkpoints_[half];
      const PathEdge& edge = top ? up_edge_ : down_edge_;
      const uint8_t* prev_row = top || h > 0 ? edge.row.data() : nullptr;  // no top half: the path starts here
      const uint8_t* prev_min = edge.min.data();
      int v = 0;  // the continued path's two row buffers alternate
      for (int s = (n - 1) / k * k; s >= 0; s -= k) {
        const int e = std::min(n, s + k);
        // the first path over [s, e), from the checkpoint at s - 1
        const uint8_t* first_row = s == 0 ? nullptr : kept.rows.data() + row_bytes * (s / k - 1);
        const uint8_t* first_min = s == 0 ? nullptr : kept.min.data() + static_cast<size_t>(cols) * (s / k - 1);
        for (int i = s; i < e; ++i) {
          const int y = row_of(half, i);
          uint8_t* cost = w.segment_costs.data() + row_bytes * (i - s);
          uint8_t* path = w.segment_paths.data() + row_bytes * (i - s);
          uint8_t* path_min = w.segment_min[(i - s) % 2].data();
          censusCostRange(census_left_.ptr<uint32_t>(y), right_reversed_.ptr<uint32_t>(y), cols, 0,
                          cols, p_.min_disparity, D, cost);
          aggregateRowVertical(cost, first_row, first_min, cols, D, pen_, simd_, path, path_min);
          first_row = path;
          first_min = path_min;
        }
        for (int i = e - 1; i >= s; --i, v ^= 1) {
          const int y = row_of(half, i);
          const uint8_t* cost = w.segment_costs.data() + row_bytes * (i - s);
          aggregateRowVertical(cost, prev_row, prev_min, cols, D, pen_, simd_, w.vertical[v].data(),
                               w.vertical_min[v].data());
          prev_row = w.vertical[v].data();
          prev_min = w.vertical_min[v].data();
          aggregateRowHorizontal(cost, cols, D, pen_, simd_, w.forward.data(), w.backward.data());
          // paths in the order the rounding avg(avg(->, <-), avg(down, up)) expects
          const uint8_t* first = w.segment_paths.data() + row_bytes * (i - s);
          const uint8_t* const paths[4] = {w.forward.data(), w.backward.data(),
                                           top ? first : w.vertical[v].data(),
                                           top ? w.vertical[v].data() : first};
          selectRowWinners(paths, cols, options, w, disparity.ptr<float>(y), confidence.ptr<float>(y));
        }
      }
    });
    PROFILE_MARK("horizontal+winners");
    // The census is undefined within half a window of the image border (its
    // code is 0 there, so every disparity costs the same): what the paths
    // carry into those pixels is a guess, biased toward the neighbours' disparity
    // (on the road the bottom rows read the row above them: too far). No
    // measurement there, so no disparity. The bottom band stays as high as the
    // main window's even where the road window has codes: the bottom-up paths
    // start there and its disparity was biased too (pitch_oscillation pitch
    // p95 0.106 -> 0.097 deg with 3 rows instead of 1; docs/stereo.md).
    invalidateBorder(disparity, confidence,
                     (road_row < rows ? std::max(p_.census_width, p_.road_census_width) : p_.census_width) / 2,
                     p_.census_height / 2, p_.census_height / 2);
    if (p_.flat_census_invalid) invalidateFlatCensus(left, census_left_, disparity, confidence);
    // 3x3 median of the disparity (as in Hirschmueller 2008 and libSGM): the
    // census winners on low-texture road scatter per pixel (+-0.4 px) and
    // neighbours differing by > 1 px split the road into tiny normal windows
    // downstream (snv_extrinsic); the median removes that scatter and fills
    // isolated invalid pixels. Measured with bench_road_disparity, docs/stereo.md
    // "Road accuracy".
    // Two fixed halves in parallel (median_fill.hpp; same result as one pass).
    disparity.copyTo(median_scratch_valid_);
    parallelTasks(threads, 2, [&](int half, int) {
      medianFillRows(median_scratch_valid_, disparity, confidence, rows * half / 2, rows * (half + 1) / 2,
                     median_scratch_[half]);
    });
    PROFILE_MARK("median");
    // Speckles in two fixed halves (the result does not depend on the thread
    // count): OpenCV's filterSpeckles is single-threaded and would otherwise
    // be a tenth of the frame time.
    parallelTasks(threads, 2, [&](int half, int) {
      removeSpeckles(disparity, &confidence, p_.speckle_window_size, p_.speckle_range,
                     rows * half / 2, rows * (half + 1) / 2, speckle_scratch_[half]);
    });
    PROFILE_MARK("speckles");
    PROFILE_MARK("final");
  }

 private:
  // Winners of one row from its four path rows {->, <-, down, up}, the
  // left-right check, and index -> pixels.
  void selectRowWinners(const uint8_t* const paths[4], int cols, const WinnerOptions& options,
                        StripeWorkspace& w, float* disp, float* conf) {
    const int D = p_.num_disparities;
    const bool check = p_.lr_max_diff >= 0;
    if (simd_) {
      selectWinnersFromPaths(paths, cols, D, p_.min_disparity, options, w.best_left.data(), disp,
                             conf, check ? w.best_right.data() : nullptr, w.sum, w.right_cost,
                             w.right_index);
    } else {  // the separate scalar steps (what the SIMD-vs-scalar test compares)
      averagePaths(paths, w.sum.size(), w.sum.data());
      selectLeftWinners(w.sum.data(), cols, D, options, w.best_left.data(), disp, conf);
      if (check)
        selectRightWinners(w.sum.data(), cols, D, p_.min_disparity, w.best_right.data(),
                           w.right_cost, w.right_index);
      if (options.subpixel) refineSubpixel(paths, cols, D, w.best_left.data(), disp);
    }
    if (check)
      leftRightCheckRow(w.best_left.data(), w.best_right.data(), cols, p_.min_disparity,
                        p_.lr_max_diff, disp, conf);
    for (int x = 0; x < cols; ++x) {
      // index -> pixels; disparity 0 (infinitely far) is "invalid" in nerv's encoding
      const float d = disp[x] < 0.0f ? 0.0f : disp[x] + static_cast<float>(p_.min_disparity);
      disp[x] = d > 0.0f ? d : 0.0f;
      if (disp[x] == 0.0f) conf[x] = 0.0f;
    }
  }

  Params p_;
  bool simd_;
  PathPenalties pen_;
  int segment_rows_;  // k: rows between the checkpoints of the first vertical path
  cv::Mat census_left_, census_right_, right_reversed_;
  // pass 2: top-down path on rows [0, h) ([0]), bottom-up on [h, rows) ([1])
  PathCheckpoints checkpoints_[2];
  PathEdge down_edge_, up_edge_;
  std::vector<StripeWorkspace> workspaces_;
  SpeckleScratch speckle_scratch_[2];
  cv::Mat median_scratch_[2], median_scratch_valid_;
};

}  // namespace

const char* ownSgmCodePaths() {
  static const std::string text = [] {
    const std::string step = pathStepPath(), winners = winnerPath();
    const std::string loops = step == winners ? "path steps and winners " + step
                                              : "path steps " + step + ", winners " + winners;
    return loops + (step == "AVX2" ? "" : " (no AVX2)") + ", census costs " + censusCostPath();
  }();
  return text.c_str();
}

std::unique_ptr<StereoMatcher> createOwnSgm(const Params& params, bool use_simd, int segment_rows) {
  return std::make_unique<OwnSgm>(params, use_simd, segment_rows);
}

}  // namespace nerv::stereo
