#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace nerv::viz {

std::string xmlEscape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::vector<double> niceTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi <= lo || target < 1) return ticks;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
    ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
  return ticks;
}

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

std::string tickLabel(double v, double step) {
  char b[32];
  const int decimals = step >= 1 ? 0 : std::min(6, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

void extend(double v, double& lo, double& hi) {
  if (!std::isfinite(v)) return;
  lo = std::min(lo, v);
  hi = std::max(hi, v);
}

}  // namespace

std::string SvgPlot::render(int width_px, int height_px) const {
  const double inf = std::numeric_limits<double>::infinity();
  double xlo = inf, xhi = -inf, ylo = inf, yhi = -inf;
  for (const auto& s : series_)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        extend(s.x[i], xlo, xhi);
        extend(s.y[i], ylo, yhi);
      }
  for (const auto& b : bars_) {
    extend(b.x0, xlo, xhi);
    extend(b.x0 + b.bin * b.counts.size(), xlo, xhi);
    extend(0, ylo, yhi);
    for (double c : b.counts) extend(c, ylo, yhi);
  }
  for (const auto& m : markers_) extend(m.x, xlo, xhi);
  const bool has_data = xlo <= xhi && ylo <= yhi;
  if (x_fixed_) { xlo = x_lo_; xhi = x_hi_; }
  if (y_fixed_) { ylo = y_lo_; yhi = y_hi_; }
  if (!(xlo <= xhi)) { xlo = 0; xhi = 1; }
  if (!(ylo <= yhi)) { ylo = 0; yhi = 1; }
  if (xhi - xlo < 1e-9) { xlo -= 0.5; xhi += 0.5; }
  if (yhi - ylo < 1e-9) { const double pad = std::max(1e-3, std::abs(ylo) * 0.05); ylo -= pad; yhi += pad; }
  if (!y_fixed_) { const double pad = (yhi - ylo) * 0.05; ylo -= pad; yhi += pad; }

  // Legend on the right, as wide as its longest entry (about 7 px per character at 12 px).
  size_t longest = 0;
  for (const auto& b : bars_) longest = std::max(longest, b.name.size());
  for (const auto& s : series_) longest = std::max(longest, s.name.size());
  for (const auto& m : markers_) longest = std::max(longest, m.name.size() + 9);
  const double left = 70, top = 30, bottom = 46;
  const double right = std::min(0.45 * width_px, 48.0 + 7.0 * static_cast<double>(longest));
  const double pw = width_px - left - right, ph = height_px - top - bottom;
  auto X = [&](double x) { return left + (x - xlo) / (xhi - xlo) * pw; };
  auto Y = [&](double y) { return top + (yhi - y) / (yhi - ylo) * ph; };

  // Clip ids must be unique within a page that holds many plots.
  static int next_id = 0;
  const std::string clip = "plotclip" + std::to_string(++next_id);
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"" << width_px << "\" height=\"" << height_px
    << "\" viewBox=\"0 0 " << width_px << ' ' << height_px << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  o << "<rect x=\"0\" y=\"0\" width=\"" << width_px << "\" height=\"" << height_px << "\" fill=\"#ffffff\"/>\n";
  o << "<text x=\"" << left << "\" y=\"18\" font-size=\"14\" font-weight=\"bold\">" << xmlEscape(title_) << "</text>\n";
  o << "<defs><clipPath id=\"" << clip << "\"><rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw
    << "\" height=\"" << ph << "\"/></clipPath></defs>\n";
  // Grid and ticks.
  const auto xt = niceTicks(xlo, xhi, 8), yt = niceTicks(ylo, yhi, 5);
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1, ystep = yt.size() > 1 ? yt[1] - yt[0] : 1;
  for (double t : xt) {
    o << "<line x1=\"" << num(X(t)) << "\" y1=\"" << top << "\" x2=\"" << num(X(t)) << "\" y2=\"" << top + ph
      << "\" stroke=\"#e5e5e5\"/>";
    o << "<text x=\"" << num(X(t)) << "\" y=\"" << top + ph + 16 << "\" text-anchor=\"middle\">" << tickLabel(t, xstep)
      << "</text>\n";
  }
  for (double t : yt) {
    o << "<line x1=\"" << left << "\" y1=\"" << num(Y(t)) << "\" x2=\"" << left + pw << "\" y2=\"" << num(Y(t))
      << "\" stroke=\"#e5e5e5\"/>";
    o << "<text x=\"" << left - 6 << "\" y=\"" << num(Y(t) + 4) << "\" text-anchor=\"end\">" << tickLabel(t, ystep)
      << "</text>\n";
  }
  o << "<rect class=\"axes\" x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"none\" stroke=\"#333\"/>\n";
  o << "<text x=\"" << num(left + pw / 2) << "\" y=\"" << height_px - 8 << "\" text-anchor=\"middle\">"
    << xmlEscape(x_label_) << "</text>\n";
  o << "<text transform=\"translate(16," << num(top + ph / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
    << xmlEscape(y_label_) << "</text>\n";
  o << "<g clip-path=\"url(#" << clip << ")\">\n";
  for (const auto& b : bars_)
    for (size_t k = 0; k < b.counts.size(); ++k) {
      if (!(b.counts[k] > 0)) continue;
      const double x1 = X(b.x0 + k * b.bin), x2 = X(b.x0 + (k + 1) * b.bin);
      o << "<rect x=\"" << num(x1) << "\" y=\"" << num(Y(b.counts[k])) << "\" width=\""
        << num(std::max(0.5, x2 - x1)) << "\" height=\"" << num(Y(0) - Y(b.counts[k])) << "\" fill=\"" << b.color
        << "\"/>";
    }
  for (const auto& s : series_) {
    std::string path;
    bool pen = false;
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        pen = false;
        continue;
      }
      path += (pen ? " L" : " M") + num(X(s.x[i])) + "," + num(Y(s.y[i]));
      pen = true;
    }
    if (!path.empty())
      o << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"" << s.width_px << "\""
        << (s.dashed ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
    if (s.points)
      for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
          o << "<circle cx=\"" << num(X(s.x[i])) << "\" cy=\"" << num(Y(s.y[i])) << "\" r=\"2.5\" fill=\"" << s.color
            << "\"/>";
  }
  for (const auto& m : markers_) {
    if (!std::isfinite(m.x)) continue;
    o << "<line x1=\"" << num(X(m.x)) << "\" y1=\"" << top << "\" x2=\"" << num(X(m.x)) << "\" y2=\"" << top + ph
      << "\" stroke=\"" << m.color << "\" stroke-width=\"2\"" << (m.dashed ? " stroke-dasharray=\"5,3\"" : "") << "/>\n";
  }
  o << "</g>\n";
  if (!has_data)
    o << "<text x=\"" << num(left + pw / 2) << "\" y=\"" << num(top + ph / 2) << "\" text-anchor=\"middle\" fill=\"#888\">"
      << "no data</text>\n";
  // Legend.
  double ly = top + 10;
  const double lx = left + pw + 14;
  auto entry = [&](const std::string& name, const std::string& color, bool dashed, bool box) {
    if (box)
      o << "<rect x=\"" << lx << "\" y=\"" << num(ly - 8) << "\" width=\"22\" height=\"10\" fill=\"" << color << "\"/>";
    else
      o << "<line x1=\"" << lx << "\" y1=\"" << num(ly - 3) << "\" x2=\"" << lx + 22 << "\" y2=\"" << num(ly - 3)
        << "\" stroke=\"" << color << "\" stroke-width=\"2\"" << (dashed ? " stroke-dasharray=\"5,3\"" : "") << "/>";
    o << "<text x=\"" << lx + 28 << "\" y=\"" << num(ly + 1) << "\">" << xmlEscape(name) << "</text>\n";
    ly += 18;
  };
  o << "<g class=\"legend\">\n";
  for (const auto& b : bars_) entry(b.name, b.color, false, true);
  for (const auto& s : series_) entry(s.name, s.color, s.dashed, false);
  for (const auto& m : markers_) {
    char v[48];
    std::snprintf(v, sizeof v, " = %.2f", m.x);
    entry(m.name + (std::isfinite(m.x) ? v : " (none)"), m.color, m.dashed, false);
  }
  o << "</g>\n</svg>\n";
  return o.str();
}

}  // namespace nerv::viz
