#pragma once
// HtmlPage: one self-contained HTML file — inline CSS, inline SVG plots and
// a few lines of inline JavaScript (a table of contents) — that needs no
// network and reads the same offline in any browser. Sections are added in
// order by the report renderers; everything given as text is escaped.
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace abbe::report {

// Where a report comes from, shown in its footer.
struct Provenance {
  std::string command_line;  // as typed (arguments quoted where needed)
  // Inputs: (name as given, SHA-256 hex of its bytes).
  std::vector<std::pair<std::string, std::string>> inputs;
  // ISO 8601 UTC; empty: report_date().
  std::string date;
};

// Now in UTC ("2026-11-25T21:04:27Z"), or the time in the environment
// variable SOURCE_DATE_EPOCH (seconds) when set, for reproducible pages.
std::string report_date();

struct Table {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // cells as text
  std::string id;                              // optional id attribute
  bool last_column_text = false;               // left-align the last column (prose)
};

// A table with its id, caption and header (rows to be added).
Table make_table(std::string id, std::string caption, std::vector<std::string> header);

class HtmlPage {
 public:
  explicit HtmlPage(std::string title);

  // A section heading (h2), listed in the table of contents; `id` must be
  // unique in the page.
  void add_section(const std::string& id, const std::string& heading);
  void add_paragraph(const std::string& text);  // escaped text
  void add_note(const std::string& text);       // a smaller, grey paragraph
  void add_table(const Table& table);
  // Figures (SVG elements from LinePlot/ColourMap) side by side, wrapping
  // to the next row when the window is narrow.
  void add_figures(const std::vector<std::string>& svgs);
  // An HTML fragment as it is (e.g. render_toolpath_view); the caller
  // escapes its text.
  void add_html(const std::string& html);
  // The footer: date, abbe version, command line, inputs and their SHA-256.
  void set_provenance(Provenance p);
  // Facts shown under the title (key: value).
  void add_fact(const std::string& key, const std::string& value);
  // Several facts, in order.
  void add_facts(std::initializer_list<std::pair<std::string, std::string>> facts);

  std::string render() const;

 private:
  std::string title_;
  std::vector<std::pair<std::string, std::string>> facts_;
  std::string body_;
  Provenance provenance_;
};

}  // namespace abbe::report
