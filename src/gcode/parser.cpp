// Runs the X3 grammar of grammar/ on one line (its semantic actions fill the
// Block) and reads programs line by line. The grammar accepts the longest
// valid prefix of a line; anything left over is explained by
// parse_diagnosis.cpp.
#include "abbe/gcode/parser.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#include "abbe/io/input_error.hpp"
#include "grammar/ast.hpp"
#include "grammar/gcode.hpp"
#include "hot.hpp"
#include "parse_diagnosis.hpp"

namespace abbe::gcode {

namespace {

// Input is read in chunks of this size (lines may be longer: the buffer grows).
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
// A line longer than this is refused: no G-code line comes near it, and a
// file without line ends (a binary file, /dev/zero) must not be buffered
// without limit.
constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;

void reset(Block& block, std::size_t line_number) {
  block.line = line_number;
  block.block_delete = false;
  block.percent = false;
  block.program_number.reset();
  block.n.reset();
  block.words.clear();
  block.checksum.reset();
  // Expression parts exist only beside code, a name or an O-word (most
  // lines of a CAM program have none: nothing to clear).
  if (block.has_code()) {
    block.code.clear();
    block.names.clear();
    block.word_expressions.clear();
    block.settings.clear();
    block.o.keyword = OKeyword::none;
    block.o.args.clear();
  }
}

std::string number_error_message(ast::NumberError error) {
  switch (error) {
    case ast::NumberError::too_long:
      static_assert(grammar::kMaxNumberChars == 64);
      return "number is too long (more than 64 characters)";
    case ast::NumberError::out_of_range:
      return "number is out of range";
    case ast::NumberError::program_number_too_large:
      return fmt::format("program number is too large (at most {})", grammar::kMaxProgramNumber);
    case ast::NumberError::checksum_too_large:
      return fmt::format("checksum is too large (at most {})", grammar::kMaxProgramNumber);
    case ast::NumberError::none:
      break;
  }
  return "bad number";
}

}  // namespace

ABBE_HOT void parse_line(std::string_view line, std::size_t line_number, const std::string& file,
                         Block& block) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (line.size() > std::numeric_limits<std::uint32_t>::max())
    throw detail::line_error(line, line_number, file, 0, "line is longer than 4 GiB");

  reset(block, line_number);
  ast::Line parsed;
  parsed.block = &block;
  parsed.line_begin = line.data();
  ast::Iterator first = line.data();
  const ast::Iterator last = line.data() + line.size();
  namespace x3 = boost::spirit::x3;
  x3::parse(first, last, x3::with<ast::line_tag>(parsed)[grammar::line()], parsed);
  // Comment strings beyond this line's comments are dropped only now, so
  // that the kept ones reuse their capacity.
  if (block.comments.size() != parsed.n_comments) block.comments.resize(parsed.n_comments);
  if (first != last)
    throw detail::explain_parse_stop(line, static_cast<std::size_t>(first - line.data()), parsed,
                                     line_number, file);
  if (parsed.error != ast::NumberError::none)
    throw detail::line_error(line, line_number, file,
                             static_cast<std::size_t>(parsed.error_at - line.data()),
                             number_error_message(parsed.error));
}

Block parse_line(std::string_view line, std::size_t line_number, const std::string& file) {
  Block block;
  parse_line(line, line_number, file, block);
  return block;
}

BlockReader::BlockReader(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

BlockReader::~BlockReader() = default;
BlockReader::BlockReader(BlockReader&&) noexcept = default;

void BlockReader::refill() {
  // Keep the unfinished line at the front; grow if it fills the buffer.
  const std::size_t kept = end_ - begin_;
  if (kept >= kMaxLineBytes)
    throw InputError(SourceLocation{file_, line_number_ + 1, 0, "", ""},
                     fmt::format("line reaches {} bytes without a line end (is this a text "
                                 "file?)",
                                 kMaxLineBytes));
  if (kept > 0 && begin_ > 0) std::memmove(buffer_.get(), buffer_.get() + begin_, kept);
  begin_ = 0;
  end_ = kept;
  if (capacity_ - kept < kChunkBytes / 2) {
    const std::size_t capacity = std::max(kChunkBytes, 2 * capacity_);
    std::unique_ptr<char[]> grown(
        new char[capacity]);  // not zero-filled: untouched pages cost nothing
    if (kept > 0) std::memcpy(grown.get(), buffer_.get(), kept);
    buffer_ = std::move(grown);
    capacity_ = capacity;
  }
  const auto wanted = static_cast<std::streamsize>(capacity_ - kept);
  in_.read(buffer_.get() + kept, wanted);
  const std::streamsize got = in_.gcount();
  end_ += static_cast<std::size_t>(got);
  if (got < wanted) {
    at_end_ = true;
    read_error_ = in_.bad();
  }
}

ABBE_HOT bool BlockReader::next_line() {
  for (;;) {
    const char* const first = buffer_.get() + begin_;
    const std::size_t available = end_ - begin_;
    if (available > 0) {
      if (const auto* lf = static_cast<const char*>(std::memchr(first, '\n', available))) {
        line_view_ = std::string_view(first, static_cast<std::size_t>(lf - first));
        begin_ += line_view_.size() + 1;
        line_ending_ = "\n";
        return true;
      }
    }
    if (at_end_) {
      // As with std::getline: the complete lines read before a read error
      // are still returned, an unfinished one is not.
      if (read_error_)
        throw InputError(SourceLocation{file_, line_number_ + 1, 0, "", ""}, "read error");
      if (available == 0) return false;
      line_view_ = std::string_view(first, available);  // the last line, without a terminator
      begin_ = end_;
      line_ending_ = "";
      return true;
    }
    refill();
  }
}

ABBE_HOT bool BlockReader::next(Block& block) {
  if (!next_line()) return false;
  ++line_number_;
  line_copied_ = false;
  if (line_number_ == 1 && line_view_.substr(0, 3) == "\xEF\xBB\xBF") {
    // A UTF-8 byte order mark (some Windows editors write one) is not part of
    // the program: drop it, offsets then refer to the line without it.
    line_view_.remove_prefix(3);
    byte_order_mark_ = true;
  }
  if (!line_view_.empty() && line_view_.back() == '\r') {
    line_view_.remove_suffix(1);
    line_ending_ = *line_ending_ != '\0' ? "\r\n" : "\r";
  }
  // The line is parsed where it lies in the read buffer; raw_line() copies
  // it only if asked.
  parse_line(line_view_, line_number_, file_, block);
  return true;
}

const std::string& BlockReader::raw_line() const {
  if (!line_copied_) {
    line_.assign(line_view_.data(), line_view_.size());
    line_copied_ = true;
  }
  return line_;
}

}  // namespace abbe::gcode
