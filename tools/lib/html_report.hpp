// A self-contained HTML page: headings, text, tables, inline SVG and images
// as base64 data: URIs, with its small stylesheet inlined. No scripts, no
// external CSS, fonts or images, so the page works offline and can be mailed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace nerv::viz {

std::string base64Encode(const std::vector<uint8_t>& bytes);

class HtmlReport {
 public:
  explicit HtmlReport(std::string title);
  void heading(const std::string& text, int level = 2);  // also a table-of-contents entry when level == 2
  void paragraph(const std::string& text);               // escaped
  void raw(const std::string& html);                     // trusted markup (e.g. an <svg> of svg_plot)
  void pre(const std::string& text);
  // Cells are escaped; numeric-looking cells are right-aligned.
  void table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  // mime e.g. "image/png"; the figure carries `caption`.
  void image(const std::vector<uint8_t>& bytes, const std::string& mime, const std::string& alt,
             const std::string& caption);
  std::string str() const;

 private:
  std::string title_;
  std::vector<std::pair<std::string, std::string>> toc_;  // anchor, text
  std::string body_;
};

}  // namespace nerv::viz
