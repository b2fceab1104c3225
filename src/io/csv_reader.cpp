#include "abbe/io/csv_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <charconv>
#include <cmath>

#include "abbe/io/input_error.hpp"

namespace abbe::io {
namespace {

char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (lower(a[i]) != lower(b[i])) return false;
  return true;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// "1,5" / "-0,25e-3": a number with a decimal comma (one comma between digits,
// no point).
bool decimal_comma_number(std::string_view t) {
  std::size_t comma = std::string_view::npos;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const char c = t[i];
    if (c == ',') {
      if (comma != std::string_view::npos) return false;
      comma = i;
    } else if (!is_digit(c) && c != '+' && c != '-' && c != 'e' && c != 'E') {
      return false;
    }
  }
  return comma != std::string_view::npos && comma > 0 && comma + 1 < t.size() &&
         is_digit(t[comma - 1]) && is_digit(t[comma + 1]);
}

}  // namespace

std::optional<double> parse_csv_number(std::string_view t) {
  if (t.empty()) return std::nullopt;
  const char* b = t.data();
  const char* e = t.data() + t.size();
  if (*b == '+') ++b;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || ptr != e || !std::isfinite(v)) return std::nullopt;
  return v;
}

CsvReader::CsvReader(std::istream& in, std::string file, Options options)
    : in_(in), file_(std::move(file)), options_(options) {}

void CsvReader::fail(std::size_t column, std::string_view field, const std::string& message) const {
  throw InputError({file_, line_, column, std::string(field), record_text_}, message);
}

bool CsvReader::read_record() {
  std::string text;
  if (!std::getline(in_, text)) return false;
  if (next_line_ == 1 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
  if (!text.empty() && text.back() == '\r') text.pop_back();
  line_ = next_line_++;
  record_text_ = text;
  record_ = std::move(text);
  // A quoted field may hold line breaks: join lines until the quotes balance.
  auto open_quote = [&]() {
    bool in_quotes = false;
    std::size_t at = 0;
    for (std::size_t i = 0; i < record_.size(); ++i)
      if (record_[i] == '"') {
        in_quotes = !in_quotes;
        if (in_quotes) at = i;
      }
    return in_quotes ? at + 1 : 0;
  };
  for (std::size_t open = open_quote(); open != 0; open = open_quote()) {
    std::string more;
    if (!std::getline(in_, more)) fail(open, "", "a quoted field is not closed (missing \")");
    ++next_line_;
    if (!more.empty() && more.back() == '\r') more.pop_back();
    record_ += '\n';
    record_ += more;
  }
  return true;
}

void CsvReader::split(char sep) {
  fields_.clear();
  storage_.clear();
  storage_.reserve(record_.size());
  spans_.clear();
  const std::string& r = record_;
  auto blank = [&](char c) { return c == ' ' || (c == '\t' && sep != '\t'); };
  std::size_t i = 0;
  for (;;) {
    while (i < r.size() && blank(r[i])) ++i;
    const std::size_t column = i + 1;
    const std::size_t begin = storage_.size();
    if (i < r.size() && r[i] == '"') {
      ++i;
      for (;;) {
        if (i >= r.size()) fail(column, "", "a quoted field is not closed (missing \")");
        if (r[i] == '"') {
          if (i + 1 < r.size() && r[i + 1] == '"') {
            storage_ += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        storage_ += r[i++];
      }
      while (i < r.size() && blank(r[i])) ++i;
      if (i < r.size() && r[i] != sep)
        fail(i + 1, "",
             fmt::format("unexpected text after the closing quote of the field at column {}",
                         column));
    } else {
      std::size_t end = i;
      while (end < r.size() && r[end] != sep) ++end;
      std::size_t last = end;
      while (last > i && blank(r[last - 1])) --last;
      storage_.append(r, i, last - i);
      i = end;
    }
    std::size_t size = storage_.size() - begin;
    if (sep != ',' && decimal_comma_number(std::string_view(storage_).substr(begin, size)))
      for (std::size_t k = begin; k < storage_.size(); ++k)
        if (storage_[k] == ',') storage_[k] = '.';
    spans_.push_back({begin, size, column});
    if (i >= r.size()) break;
    ++i;  // the separator
  }
  fields_.reserve(spans_.size());
  for (const Span& s : spans_)
    fields_.push_back({std::string_view(storage_).substr(s.begin, s.size), s.column});
}

void CsvReader::read_header() {
  for (;;) {
    if (!read_record()) {
      if (line_ == 0) line_ = 1;
      fail(1, "header", "empty file: a header line is required");
    }
    const std::string_view t = trim_blanks(record_);
    if (!t.empty() && (options_.comment == '\0' || t.front() != options_.comment)) break;
  }
  // The separator: the most frequent of , ; and tab outside quotes (a tie
  // goes to the comma, then the semicolon).
  std::array<std::size_t, 3> count{0, 0, 0};
  bool in_quotes = false;
  for (char c : record_) {
    if (c == '"') in_quotes = !in_quotes;
    if (in_quotes) continue;
    if (c == ',') ++count[0];
    if (c == ';') ++count[1];
    if (c == '\t') ++count[2];
  }
  sep_ = ',';
  if (count[1] > count[0] && count[1] >= count[2]) sep_ = ';';
  if (count[2] > count[0] && count[2] > count[1]) sep_ = '\t';
  split(sep_);
  header_.clear();
  for (const CsvField& f : fields_) {
    std::string name(f.text);
    for (char& c : name) c = lower(c);
    header_.push_back(std::move(name));
  }
  for (std::size_t a = 0; a < header_.size(); ++a)
    for (std::size_t b = a + 1; b < header_.size(); ++b)
      if (!header_[a].empty() && header_[a] == header_[b])
        fail(fields_[b].column, header_[b], fmt::format("column `{}` appears twice", header_[b]));
}

std::optional<std::size_t> CsvReader::column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (same_name(header_[i], name)) return i;
  return std::nullopt;
}

void CsvReader::find_columns(const std::string_view* names, std::size_t count, std::size_t required,
                             std::string_view needs, int* out) const {
  for (std::size_t k = 0; k < count; ++k) {
    const auto c = column(names[k]);
    out[k] = c ? static_cast<int>(*c) : -1;
  }
  for (std::size_t k = 0; k < required && k < count; ++k)
    if (out[k] < 0)
      fail(1, "header",
           fmt::format("the header has no `{}` column ({}; found: {})", names[k], needs,
                       fmt::join(header_, ", ")));
}

bool CsvReader::next() {
  while (read_record()) {
    const std::string_view t = trim_blanks(record_);
    if (t.empty() || (options_.comment != '\0' && t.front() == options_.comment)) continue;
    split(sep_);
    return true;
  }
  return false;
}

const CsvField& CsvReader::field(std::size_t index, std::string_view name) const {
  if (index >= fields_.size())
    fail(record_text_.size() + 1, name,
         fmt::format("{} fields, but `{}` is column {}", fields_.size(), name, index + 1));
  return fields_[index];
}

std::optional<CsvField> CsvReader::present_field(int index, std::string_view name) const {
  if (index < 0) return std::nullopt;
  const CsvField& f = field(static_cast<std::size_t>(index), name);
  if (f.text.empty()) return std::nullopt;
  return f;
}

std::optional<double> CsvReader::number(const CsvField& f, std::string_view name) const {
  if (f.text.empty()) return std::nullopt;
  const auto v = parse_csv_number(f.text);
  if (!v) fail(f.column, name, fmt::format("\"{}\" is not a finite number", f.text));
  return v;
}

}  // namespace abbe::io
