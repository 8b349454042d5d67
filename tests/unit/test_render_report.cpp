// The report's building blocks: SVG plots, ticks, base64, escaping, the page.
#include <gtest/gtest.h>

#include <cmath>

#include "html_report.hpp"
#include "svg_plot.hpp"

using namespace nerv::viz;

namespace {
int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

TEST(renderReport, Base64KnownVectors) {
  auto b = [](const std::string& s) { return base64Encode(std::vector<uint8_t>(s.begin(), s.end())); };
  EXPECT_EQ(b(""), "");
  EXPECT_EQ(b("M"), "TQ==");
  EXPECT_EQ(b("Ma"), "TWE=");
  EXPECT_EQ(b("Man"), "TWFu");
  EXPECT_EQ(b("any carnal pleasure."), "YW55IGNhcm5hbCBwbGVhc3VyZS4=");
  EXPECT_EQ(base64Encode({0xff, 0xfe, 0x00}), "//4A");
}

TEST(renderReport, NiceTicks) {
  EXPECT_EQ(niceTicks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  const auto t = niceTicks(-0.13, 0.42, 5);
  ASSERT_FALSE(t.empty());
  // range 0.55 / 5 ticks = 0.11 -> the next of 1, 2, 5 x 10^k is 0.2
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t[0], 0.0, 1e-12);
  EXPECT_NEAR(t[2], 0.4, 1e-12);
  EXPECT_TRUE(niceTicks(1, 1, 5).empty());
  EXPECT_TRUE(niceTicks(0, NAN, 5).empty());
}

TEST(renderReport, XmlEscape) { EXPECT_EQ(xmlEscape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;"); }

TEST(renderReport, PlotHasAxesLegendSeriesAndMarkers) {
  SvgPlot p("Pitch <test>", "frame seq", "pitch [deg]");
  SvgSeries s;
  s.name = "filtered";
  s.x = {0, 1, 2, 3};
  s.y = {0.5, NAN, 0.7, 0.6};  // the NaN breaks the line into two pieces
  p.add(s);
  SvgBars b;
  b.name = "histogram";
  b.x0 = 0;
  b.bin = 0.5;
  b.counts = {1, 0, 3};
  p.add(b);
  p.add(SvgMarker{"mode", 1.25, "#ff0000", false});
  const std::string svg = p.render(800, 240);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("Pitch &lt;test&gt;"), std::string::npos);
  EXPECT_NE(svg.find("frame seq"), std::string::npos);
  EXPECT_NE(svg.find("pitch [deg]"), std::string::npos);
  EXPECT_NE(svg.find(">filtered<"), std::string::npos);
  EXPECT_NE(svg.find(">histogram<"), std::string::npos);
  EXPECT_NE(svg.find("mode = 1.25"), std::string::npos);
  EXPECT_EQ(count(svg, " M"), 2);           // two line pieces
  EXPECT_EQ(count(svg, "fill=\"#9ecae1\""), 3);  // two bars + the legend swatch
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("no data"), std::string::npos);
  // Two plots on one page do not share a clip id.
  const std::string other = p.render();
  const auto id = [](const std::string& s) { const size_t a = s.find("clipPath id=\""); return s.substr(a, s.find('"', a + 13) - a); };
  EXPECT_NE(id(svg), id(other));
}

TEST(renderReport, EmptyPlotSaysNoData) {
  SvgPlot p("empty", "x", "y");
  SvgSeries s;
  s.name = "nothing";
  s.x = {0, 1};
  s.y = {NAN, NAN};
  p.add(s);
  const std::string svg = p.render();
  EXPECT_NE(svg.find("no data"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(renderReport, PageIsSelfContained) {
  HtmlReport page("run <1>");
  page.heading("Summary");
  page.paragraph("a & b");
  page.table({"k", "v"}, {{"frames", "10"}, {"name", "x<y"}});
  page.image({1, 2, 3}, "image/png", "alt", "caption");
  page.raw("<svg></svg>");
  const std::string html = page.str();
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("<title>run &lt;1&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("href=\"#s1\""), std::string::npos);
  EXPECT_NE(html.find("id=\"s1\""), std::string::npos);
  EXPECT_NE(html.find("a &amp; b"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"n\">10</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>x&lt;y</td>"), std::string::npos);
  EXPECT_NE(html.find("src=\"data:image/png;base64,AQID\""), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org") == std::string::npos ? std::string::npos : html.find("http://"));
  EXPECT_EQ(html.find("<link"), std::string::npos);
}
