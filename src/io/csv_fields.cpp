#include "abbe/io/csv_fields.hpp"

namespace abbe::io {

std::string_view trim_blanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<CsvField> split_csv_line(std::string_view line) {
  std::vector<CsvField> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i)
    if (i == line.size() || line[i] == ',') {
      out.push_back({line.substr(start, i - start), start + 1});
      start = i + 1;
    }
  return out;
}

}  // namespace abbe::io
