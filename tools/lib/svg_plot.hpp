// A small SVG plot writer for the run report: line series, histogram bars and
// vertical markers on linear axes with ticks, axis titles (with units) and a
// legend. Output is one self-contained <svg> element (no scripts, no fonts
// beyond the generic "sans-serif").
#pragma once

#include <string>
#include <vector>

namespace nerv::viz {

struct SvgSeries {
  std::string name;
  std::vector<double> x, y;   // same length; non-finite y breaks the line
  std::string color = "#1f77b4";
  double width_px = 1.5;
  bool dashed = false;
  bool points = false;        // draw a dot at each sample as well
};

struct SvgBars {
  std::string name;
  double x0 = 0, bin = 1;     // bar k covers [x0 + k*bin, x0 + (k+1)*bin)
  std::vector<double> counts;
  std::string color = "#9ecae1";
};

struct SvgMarker {
  std::string name;           // shown in the legend with its value
  double x = 0;
  std::string color = "#d62728";
  bool dashed = false;
};

class SvgPlot {
 public:
  SvgPlot(std::string title, std::string x_label, std::string y_label)
      : title_(std::move(title)), x_label_(std::move(x_label)), y_label_(std::move(y_label)) {}

  void add(const SvgSeries& s) { series_.push_back(s); }
  void add(const SvgBars& b) { bars_.push_back(b); }
  void add(const SvgMarker& m) { markers_.push_back(m); }
  // Fixed axis ranges; by default they fit the data.
  void setXRange(double lo, double hi) { x_fixed_ = true; x_lo_ = lo; x_hi_ = hi; }
  void setYRange(double lo, double hi) { y_fixed_ = true; y_lo_ = lo; y_hi_ = hi; }

  // The <svg> element. With no finite data it still draws the frame and says "no data".
  std::string render(int width_px = 960, int height_px = 280) const;

 private:
  std::string title_, x_label_, y_label_;
  std::vector<SvgSeries> series_;
  std::vector<SvgBars> bars_;
  std::vector<SvgMarker> markers_;
  bool x_fixed_ = false, y_fixed_ = false;
  double x_lo_ = 0, x_hi_ = 1, y_lo_ = 0, y_hi_ = 1;
};

// Tick positions at 1, 2 or 5 x 10^k covering [lo, hi] with about `target` ticks.
std::vector<double> niceTicks(double lo, double hi, int target = 6);

// &, <, >, " escaped for XML text and attributes.
std::string xmlEscape(const std::string& s);

}  // namespace nerv::viz
