// Does the ThreadSanitizer set-up of `tools/nerv tsan` work? A cv::parallel_for_ over disjoint
// rows must give no report with the shim preloaded (parallel_for_shim.cpp), and the same loop
// with a counter every stripe increments unguarded ("race") must give one: the stripes ran on
// two threads and TSan saw them.
#include <opencv2/core.hpp>

#include <cstdio>
#include <cstring>
#include <vector>

int main(int argc, char** argv) {
  const bool race = argc > 1 && std::strcmp(argv[1], "race") == 0;
  std::vector<int> rows(64, 0);
  int shared = 0;
  cv::parallel_for_(cv::Range(0, 64), [&](const cv::Range& r) {
    for (int i = r.start; i < r.end; ++i) rows[i] = i;  // disjoint: no race
    if (race) ++shared;                                 // every stripe, unguarded
    cv::Mat m(200, 200, CV_32F);                        // some work, so that stripes overlap in time
    cv::randu(m, 0, 1);
    (void)cv::sum(m);
  });
  long sum = 0;
  for (int v : rows) sum += v;
  std::printf("sum %ld (2016 expected), stripes counted %d\n", sum, shared);
  return sum == 2016 ? 0 : 1;
}
