#include "abbe/report/html_page.hpp"

#include <fmt/format.h>

#include "abbe/io/utc_timestamp.hpp"
#include "abbe/report/svg.hpp"

namespace abbe::report {
namespace {

constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", Arial, sans-serif; margin: 24px; color: #222; background: #fafafa;
       line-height: 1.3; }
h1 { font-size: 24px; margin-bottom: 4px; }
h2 { font-size: 19px; margin-top: 32px; border-bottom: 1px solid #ccc; padding-bottom: 4px; }
h3 { font-size: 16px; margin-top: 20px; }
.facts { color: #444; margin: 4px 0 16px 0; }
.facts span { margin-right: 18px; }
.note { color: #666; font-size: 13px; }
.figures { display: flex; flex-wrap: wrap; gap: 12px; }
.figures svg { border: 1px solid #ddd; background: #fff; }
table { border-collapse: collapse; margin: 8px 0 16px 0; background: #fff; }
caption { text-align: left; font-weight: bold; padding: 4px 0; }
th, td { border: 1px solid #ccc; padding: 4px 10px; text-align: right; }
th { background: #eee; }
td:first-child, th:first-child, td.text, th.text { text-align: left; }
#toc { font-size: 14px; }
#toc a { margin-right: 14px; }
footer { margin-top: 32px; border-top: 1px solid #ccc; padding-top: 8px; color: #555; font-size: 13px; }
footer code { font-size: 12px; word-break: break-all; }
)";

// Builds the table of contents from the h2 headings (the page reads fine
// without it).
constexpr const char* kScript = R"(
(function () {
  var toc = document.getElementById('toc');
  if (!toc) return;
  var hs = document.querySelectorAll('h2[id]');
  for (var i = 0; i < hs.length; i++) {
    var a = document.createElement('a');
    a.href = '#' + hs[i].id;
    a.textContent = hs[i].textContent;
    toc.appendChild(a);
  }
  var n = document.querySelectorAll('svg.plot, figure.toolpath-3d').length;
  var f = document.getElementById('plot-count');
  if (f) f.textContent = n + ' plots';
})();
)";

}  // namespace

std::string report_date() { return io::utc_timestamp(); }

HtmlPage::HtmlPage(std::string title) : title_(std::move(title)) {}

void HtmlPage::add_section(const std::string& id, const std::string& heading) {
  body_ += fmt::format("<h2 id=\"{}\">{}</h2>\n", escape_xml(id), escape_xml(heading));
}

void HtmlPage::add_paragraph(const std::string& text) {
  body_ += fmt::format("<p>{}</p>\n", escape_xml(text));
}

void HtmlPage::add_note(const std::string& text) {
  body_ += fmt::format("<p class=\"note\">{}</p>\n", escape_xml(text));
}

void HtmlPage::add_table(const Table& t) {
  body_ += t.id.empty() ? "<table>" : fmt::format("<table id=\"{}\">", escape_xml(t.id));
  if (!t.caption.empty()) body_ += fmt::format("<caption>{}</caption>", escape_xml(t.caption));
  body_ += "\n<tr>";
  for (std::size_t i = 0; i < t.header.size(); ++i)
    body_ +=
        fmt::format(t.last_column_text && i + 1 == t.header.size() ? "<th class=\"text\">{}</th>"
                                                                   : "<th>{}</th>",
                    escape_xml(t.header[i]));
  body_ += "</tr>\n";
  for (const auto& row : t.rows) {
    body_ += "<tr>";
    for (std::size_t i = 0; i < row.size(); ++i)
      body_ += fmt::format(
          t.last_column_text && i + 1 == row.size() ? "<td class=\"text\">{}</td>" : "<td>{}</td>",
          escape_xml(row[i]));
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

void HtmlPage::add_figures(const std::vector<std::string>& svgs) {
  body_ += "<div class=\"figures\">\n";
  for (const auto& s : svgs) body_ += s;
  body_ += "</div>\n";
}

void HtmlPage::add_html(const std::string& html) { body_ += html; }

void HtmlPage::set_provenance(Provenance p) { provenance_ = std::move(p); }

void HtmlPage::add_fact(const std::string& key, const std::string& value) {
  facts_.emplace_back(key, value);
}

void HtmlPage::add_facts(std::initializer_list<std::pair<std::string, std::string>> facts) {
  for (const auto& f : facts) facts_.push_back(f);
}

Table make_table(std::string id, std::string caption, std::vector<std::string> header) {
  Table t;
  t.id = std::move(id);
  t.caption = std::move(caption);
  t.header = std::move(header);
  return t;
}

std::string HtmlPage::render() const {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += fmt::format("<title>{}</title>\n<style>{}</style>\n</head>\n<body>\n", escape_xml(title_),
                   kStyle);
  o += fmt::format("<h1>{}</h1>\n<div class=\"facts\">", escape_xml(title_));
  for (const auto& [k, v] : facts_)
    o += fmt::format("<span><b>{}:</b> {}</span>", escape_xml(k), escape_xml(v));
  o += "</div>\n<nav id=\"toc\"></nav>\n";
  o += body_;
  o += fmt::format(
      "<footer id=\"provenance\"><div>made {} by abbe {} &#183; <span id=\"plot-count\"></span> "
      "&#183; hover over a curve, a cell or the 3-D toolpath for its values</div>\n",
      escape_xml(provenance_.date.empty() ? report_date() : provenance_.date), ABBE_VERSION);
  if (!provenance_.command_line.empty())
    o += fmt::format("<div>command: <code>{}</code></div>\n", escape_xml(provenance_.command_line));
  for (const auto& [name, hash] : provenance_.inputs)
    o += fmt::format("<div>input {}: SHA-256 <code>{}</code></div>\n", escape_xml(name),
                     escape_xml(hash));
  o += fmt::format("</footer>\n<script>{}</script>\n</body>\n</html>\n", kScript);
  return o;
}

}  // namespace abbe::report
