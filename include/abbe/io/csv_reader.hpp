#pragma once
// CsvReader: the one reader of CSV files in abbe, for files as people save
// them: a UTF-8 byte-order mark (Excel), `,` `;` or tab as separator (found
// on the header line), fields in double quotes ("" for a quote, separators
// and line breaks inside), blanks around fields, CRLF line ends,
// case-insensitive header names, blank lines and (optionally) comment lines.
// In a file separated by `;` or tabs, a number written with a decimal comma
// ("1,5") reads as 1.5. Every field keeps its 1-based line and column, so
// errors name file, line and column (docs/formats.md).
#include <array>
#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "abbe/io/csv_fields.hpp"

namespace abbe::io {

class CsvReader {
 public:
  struct Options {
    char comment = '\0';  // lines starting (after blanks) with this are skipped; '\0': none
  };

  CsvReader(std::istream& in, std::string file, Options options);
  CsvReader(std::istream& in, std::string file) : CsvReader(in, std::move(file), Options{}) {}

  // Reads the header (the first record that is neither blank nor a comment) and chooses the
  // separator. Throws an InputError (field "header") for an input without one.
  void read_header();
  // The index of the header column named `name` (compared without case);
  // nullopt when there is none. Throws for a name that appears twice.
  std::optional<std::size_t> column(std::string_view name) const;
  const std::vector<std::string>& header_names() const { return header_; }  // lower case
  // The header index of every one of `names` (−1 where there is no such
  // column). Fails (field "header") naming the first of the leading
  // `required` names without a column: "the header has no `NAME` column
  // (NEEDS; found: the header's names)".
  template <std::size_t N>
  std::array<int, N> columns(const std::array<std::string_view, N>& names, std::size_t required,
                             std::string_view needs) const {
    std::array<int, N> col;
    find_columns(names.data(), N, required, needs, col.data());
    return col;
  }

  // The next record that is not blank (nor a comment); false at the end.
  bool next();
  // The fields of the current record: unquoted, trimmed text and the column
  // of its first character (valid until the next call of next()).
  const std::vector<CsvField>& fields() const { return fields_; }
  std::size_t line() const { return line_; }                     // of the current record
  const std::string& line_text() const { return record_text_; }  // its first line, as written
  char separator() const { return sep_; }
  const std::string& file() const { return file_; }

  // An InputError at `column` of the current record (0: unknown), naming `field`.
  [[noreturn]] void fail(std::size_t column, std::string_view field,
                         const std::string& message) const;
  // The field at header index `index` of the current record, or a failure
  // naming `name` when the record is shorter.
  const CsvField& field(std::size_t index, std::string_view name) const;
  // The field at header index `index` (as columns() gives it: −1 for a
  // column the header does not have), nullopt when there is no such column
  // or the field is empty; a failure naming `name` when the record is shorter.
  std::optional<CsvField> present_field(int index, std::string_view name) const;
  // The field as a finite number (a leading '+' allowed); nullopt when it is
  // empty; a failure naming `name` and the column when it is not a number.
  std::optional<double> number(const CsvField& f, std::string_view name) const;

 private:
  bool read_record();
  void split(char sep);
  void find_columns(const std::string_view* names, std::size_t count, std::size_t required,
                    std::string_view needs, int* out) const;

  std::istream& in_;
  std::string file_;
  Options options_;
  char sep_ = ',';
  std::size_t next_line_ = 1;  // number of the next physical line
  std::size_t line_ = 0;
  std::string record_text_;  // the first physical line of the record
  std::string record_;       // the whole record (lines joined by '\n' inside quotes)
  std::string storage_;      // unquoted field texts, fields_ view into it
  struct Span {
    std::size_t begin, size, column;
  };
  std::vector<Span> spans_;
  std::vector<CsvField> fields_;
  std::vector<std::string> header_;
};

// A number as CSV files write it: optional '+', then what std::from_chars
// reads, finite, nothing after it. nullopt otherwise.
std::optional<double> parse_csv_number(std::string_view text);

}  // namespace abbe::io
