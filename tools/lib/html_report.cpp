#include "html_report.hpp"

#include <cctype>

#include "svg_plot.hpp"

namespace nerv::viz {

std::string base64Encode(const std::vector<uint8_t>& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += alphabet[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const uint32_t v = (uint32_t(bytes[i]) << 16) | (two ? uint32_t(bytes[i + 1]) << 8 : 0);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += two ? alphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::heading(const std::string& text, int level) {
  const std::string anchor = "s" + std::to_string(toc_.size() + 1);
  if (level == 2) toc_.push_back({anchor, text});
  const std::string h = "h" + std::to_string(level);
  body_ += "<" + h + (level == 2 ? " id=\"" + anchor + "\"" : "") + ">" + xmlEscape(text) + "</" + h + ">\n";
}

void HtmlReport::paragraph(const std::string& text) { body_ += "<p>" + xmlEscape(text) + "</p>\n"; }

void HtmlReport::raw(const std::string& html) { body_ += html + "\n"; }

void HtmlReport::pre(const std::string& text) { body_ += "<pre>" + xmlEscape(text) + "</pre>\n"; }

void HtmlReport::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  auto numeric = [](const std::string& s) {
    if (s.empty()) return false;
    for (char c : s)
      if (!std::isdigit(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '+' && c != '%' && c != ' ')
        return false;
    return true;
  };
  std::string t = "<table>\n<tr>";
  for (const auto& h : header) t += "<th>" + xmlEscape(h) + "</th>";
  t += "</tr>\n";
  for (const auto& row : rows) {
    t += "<tr>";
    for (const auto& c : row) t += (numeric(c) ? "<td class=\"n\">" : "<td>") + xmlEscape(c) + "</td>";
    t += "</tr>\n";
  }
  body_ += t + "</table>\n";
}

void HtmlReport::image(const std::vector<uint8_t>& bytes, const std::string& mime, const std::string& alt,
                       const std::string& caption) {
  body_ += "<figure><img alt=\"" + xmlEscape(alt) + "\" src=\"data:" + mime + ";base64," + base64Encode(bytes) +
           "\"><figcaption>" + xmlEscape(caption) + "</figcaption></figure>\n";
}

std::string HtmlReport::str() const {
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + xmlEscape(title_) +
      "</title>\n<style>\n"
      "body{font-family:sans-serif;margin:24px;color:#222;max-width:1320px}\n"
      "h1{font-size:22px}h2{font-size:18px;border-bottom:1px solid #ccc;padding-bottom:4px;margin-top:32px}\n"
      "table{border-collapse:collapse;margin:8px 0}td,th{border:1px solid #ccc;padding:3px 8px;font-size:13px}\n"
      "th{background:#f0f0f0}td.n{text-align:right;font-variant-numeric:tabular-nums}\n"
      "pre{background:#f7f7f7;padding:8px;font-size:12px;overflow-x:auto}\n"
      "figure{margin:12px 0}img{max-width:100%;border:1px solid #ccc}figcaption{font-size:13px;color:#555}\n"
      "svg.plot{display:block;margin:8px 0;border:1px solid #ddd}\n"
      "</style>\n</head>\n<body>\n<h1>" +
      xmlEscape(title_) + "</h1>\n<nav><ul>\n";
  for (const auto& [anchor, text] : toc_) page += "<li><a href=\"#" + anchor + "\">" + xmlEscape(text) + "</a></li>\n";
  page += "</ul></nav>\n" + body_ + "</body>\n</html>\n";
  return page;
}

}  // namespace nerv::viz
