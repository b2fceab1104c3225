// Parameters, expressions and O-word control flow of RS274/NGC, as
// LinuxCNC's rs274ngc executes them, between the BlockReader and the
// Interpreter:
// - a block's words are evaluated first, then its parameter settings take
//   effect (all reads of a line see the values from before the line), then
//   the interpreter executes it;
// - plain lines stream through; from the first O-word on, the lines read are
//   kept (text and parsed block) so that loops and calls can go back;
// - the control flow is rs274ngc's own state machine (LinuxCNC 2.9,
//   interp_o_word.cc), so that programs that lean on its details behave
//   the same: each label's first line is remembered (loops jump back to it,
//   calls to the "sub" line); going forward means skipping to the next
//   O-word line with a given label; "if" keeps one executed flag, "break"
//   and "continue" one flag each (a break out of a while nested in a do
//   also ends the do, as rs274ngc does);
// - a sub ... endsub is skipped where it stands; a call of a subroutine
//   not seen yet opens name.ngc in the subroutine folder, else skips
//   forward in the file to its "sub" line;
// - loops are bounded (DialectOptions::loop_limit jumps back in all) and
//   calls nest at most kMaxCallDepth deep.
#include "program_runner.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"
#include "expression_eval.hpp"
#include "parameters.hpp"

namespace abbe::gcode::detail {

namespace {

constexpr std::size_t kMaxCallDepth = 10;  // as rs274ngc (checked: LinuxCNC's factorial.ngc)

struct StoredLine {
  std::string text;
  Block block;
};

// The lines of one file kept for going back.
struct Source {
  std::string file;
  BlockReader* reader = nullptr;  // more lines to come (main file), else complete
  std::vector<std::unique_ptr<StoredLine>> lines;

  // Line i, reading on as needed; nullptr past the end.
  StoredLine* at(std::size_t i) {
    while (i >= lines.size()) {
      if (reader == nullptr) return nullptr;
      auto stored = std::make_unique<StoredLine>();
      if (!reader->next(stored->block)) {
        reader = nullptr;
        return nullptr;
      }
      stored->text = reader->raw_line();
      lines.push_back(std::move(stored));
    }
    return lines[i].get();
  }
};

struct Place {
  Source* source = nullptr;
  std::size_t index = 0;
};

// What rs274ngc remembers about a label: the line where it was first seen.
struct Label {
  OKeyword keyword = OKeyword::none;
  Place at;
  long repeat_count = -1;  // repeat: iterations left, -1 = not started
};

struct Frame {
  Place return_to;  // the line after the call
  Place call;
};

class Runner {
 public:
  Runner(const std::string& file, const InterpreterConfig& config, const MotionSink& sink,
         ProgramStats& stats)
      : config_(config), interpreter_(config, file), sink_(sink), stats_(stats) {
    const Interpreter* interp = &interpreter_;
    const InterpreterConfig* cfg = &config_;
    parameters_.live = [interp, cfg](int n) -> std::optional<double> {
      if (n == 5220) return interp->modal().coord_index + 1.0;
      if (n == 5400) return static_cast<double>(interp->modal().tool_in_spindle);
      if (n >= 5420 && n <= 5428) {
        if (n > 5422) return 0.0;
        return interp->program_position()[n - 5420];
      }
      if (n >= 5221 && n < 5221 + 20 * 6) {
        const int k = (n - 5221) / 20;
        const int axis = (n - 5221) % 20;
        if (axis < 3) return cfg->work_offsets[static_cast<std::size_t>(k)][axis];
      }
      return std::nullopt;
    };
    parameters_.live_named = [this](const std::string& name) -> std::optional<double> {
      if (name == "_line") return static_cast<double>(current_line_);
      if (name == "_call_level") return static_cast<double>(frames_.size());
      return interpreter_.predefined_parameter(name);
    };
    if (!config.dialect.var_file.empty()) parameters_.read_var_file(config.dialect.var_file);
  }

  // Motions cutter radius compensation still holds back at the end.
  void finish() {
    interpreter_.finish(sink_);
    stats_.motions = interpreter_.motions_delivered();
  }

  void run(std::istream& in, const std::string& file) {
    BlockReader reader(in, file);
    Block block;
    // Streaming until the first O-word.
    while (!interpreter_.program_ended() && reader.next(block)) {
      if (block.o.keyword != OKeyword::none) {
        main_.file = file;
        main_.reader = &reader;
        auto stored = std::make_unique<StoredLine>();
        stored->block = std::move(block);
        stored->text = reader.raw_line();
        main_.lines.push_back(std::move(stored));
        run_from(Place{&main_, 0});
        return;
      }
      execute(block, reader.line_text(), file);
    }
  }

 private:
  void execute(Block& block, std::string_view text, const std::string& file) {
    ++stats_.lines;
    current_line_ = block.line;
    if (block.has_code()) evaluate_codes(block, text, file);
    interpreter_.execute_evaluated(block, text, sink_);
  }

  // The block's computed word values and parameter settings. Out of line:
  // a CAM program's plain blocks have none.
  [[gnu::noinline]] void evaluate_codes(Block& block, std::string_view text,
                                        const std::string& file) {
    {
      const CodeSite s{file, block.line, text};
      for (const WordExpression& w : block.word_expressions)
        block.words[w.word].value = evaluate(block, w.code, parameters_, s);
      if (!block.settings.empty()) {
        // Read every value first, then set (rs274ngc's rule).
        struct Pending {
          int number;
          std::int32_t name;
          double value;
        };
        std::vector<Pending> pending;
        for (const ParameterSetting& p : block.settings) {
          if (p.name >= 0 && parameters_.read_only(block.names[static_cast<std::size_t>(p.name)]))
            fail_at(s, p.column,
                    fmt::format("cannot assign to the read-only parameter #<{}>",
                                block.names[static_cast<std::size_t>(p.name)]));
          int n = 0;
          if (p.name < 0) {
            n = integer_value(evaluate(block, p.index, parameters_, s), s, p.column,
                              "a parameter number");
            if (!ParameterStore::valid(n))
              fail_at(s, p.column,
                      fmt::format("parameter number #{} is out of range (1 to {})", n,
                                  ParameterStore::kCount - 1));
          }
          pending.push_back(Pending{n, p.name, evaluate(block, p.value, parameters_, s)});
        }
        for (const Pending& p : pending) {
          if (p.name >= 0)
            parameters_.set(block.names[static_cast<std::size_t>(p.name)], p.value);
          else
            parameters_.set(p.number, p.value);
        }
      }
    }
  }

  const StoredLine& line_at(const Place& at) const { return *at.source->lines[at.index]; }

  [[noreturn]] void fail(const Place& at, std::uint32_t column, const std::string& message) {
    const StoredLine& l = line_at(at);
    fail_at(CodeSite{at.source->file, l.block.line, l.text}, column, message);
  }
  [[noreturn]] void fail(const Place& at, const std::string& message) {
    fail(at, line_at(at).block.o.column, message);
  }

  double argument(const Place& at, std::size_t i) {
    StoredLine& l = *at.source->lines[at.index];
    return evaluate(l.block, l.block.o.args[i], parameters_,
                    CodeSite{at.source->file, l.block.line, l.text});
  }

  static std::string label_text(const std::string& label) {
    return (!label.empty() && label[0] >= '0' && label[0] <= '9') ? "o" + label
                                                                  : "o<" + label + ">";
  }
  static std::string what(const OWord& o) {
    return label_text(o.label) + " " + o_keyword_name(o.keyword);
  }

  // The condition of if/elseif/while/repeat: exactly one [...].
  double condition(const Place& at) {
    const OWord& o = line_at(at).block.o;
    if (o.args.size() != 1)
      fail(at, o.keyword_column, fmt::format("{} needs one [...] argument", what(o)));
    return argument(at, 0);
  }

  void count_iteration(const Place& at) {
    if (++iterations_ > config_.dialect.loop_limit)
      fail(at, fmt::format("more than {} loop iterations ({}): a runaway loop? (the limit is "
                           "--loop-limit)",
                           config_.dialect.loop_limit, what(line_at(at).block.o)));
  }

  // The label's first line; rs274ngc refuses a label used by two constructs.
  Label* find(const std::string& label) {
    const auto it = labels_.find(label);
    return it == labels_.end() ? nullptr : &it->second;
  }
  Label& remember(const Place& at) {
    const OWord& o = line_at(at).block.o;
    return labels_[o.label] = Label{o.keyword, at, -1};
  }
  // if, while, repeat: a second construct with the same label is an error.
  void remember_once(const Place& at, bool do_end_allowed) {
    const OWord& o = line_at(at).block.o;
    if (Label* l = find(o.label)) {
      const bool same_line = l->at.source == at.source && l->at.index == at.index;
      if (!same_line && !(do_end_allowed && l->keyword == OKeyword::do_))
        fail(at, fmt::format("duplicate O-word label {} (first used in line {})",
                             label_text(o.label), line_at(l->at).block.line));
    } else {
      remember(at);
    }
  }
  // elseif, else, endif, break, continue, endwhile, endrepeat: their label
  // must have been opened by the right construct.
  Label& opened_by(const Place& at, std::initializer_list<OKeyword> keywords) {
    const OWord& o = line_at(at).block.o;
    Label* l = find(o.label);
    if (l == nullptr) fail(at, fmt::format("{} without its opening line", what(o)));
    for (OKeyword k : keywords)
      if (l->keyword == k) return *l;
    fail(at, fmt::format("{} does not match the {} {} in line {}", what(o), label_text(o.label),
                         o_keyword_name(l->keyword), line_at(l->at).block.line));
  }

  void skip_to(const std::string& label, const Place& from) {
    skipping_ = label;
    skip_start_ = from;
  }

  // Jumps to the remembered line of `label` (loops: the opening line, calls:
  // the sub line). Returns false if the label is unknown.
  bool back_to(const std::string& label, Place& pc) {
    Label* l = find(label);
    if (l == nullptr) return false;
    pc = l->at;
    return true;
  }

  // o<name> call: the sub line, a file of the subroutine folder, or skipping
  // forward to "o<name> sub".
  void call(const Place& here, Place& pc) {
    const OWord& o = line_at(here).block.o;
    if (frames_.size() >= kMaxCallDepth)
      fail(here, fmt::format("subroutine calls nested more than {} deep", kMaxCallDepth));
    std::vector<double> args;
    for (std::size_t i = 0; i < o.args.size(); ++i) args.push_back(argument(here, i));
    if (args.size() > static_cast<std::size_t>(ParameterStore::kCallArguments))
      fail(here, "more than 30 arguments in a call");
    frames_.push_back(Frame{pc, here});
    parameters_.enter_call(args);
    interpreter_.enter_call();
    if (back_to(o.label, pc)) return;
    if (!config_.dialect.subroutine_path.empty()) {
      const std::string path = config_.dialect.subroutine_path + "/" + o.label + ".ngc";
      std::ifstream in(path);
      if (in) {
        auto source = std::make_unique<Source>();
        source->file = path;
        BlockReader reader(in, path);
        source->reader = &reader;
        while (source->at(source->lines.size()) != nullptr) {
        }
        source->reader = nullptr;
        sub_files_.push_back(std::move(source));
        skipping_ = o.label;
        skipping_to_sub_ = o.label;
        skip_start_ = here;
        pc = Place{sub_files_.back().get(), 0};
        return;
      }
    }
    skipping_ = o.label;
    skipping_to_sub_ = o.label;
    skip_start_ = here;
  }

  void do_return(const Place& here, Place& pc, const OWord& o) {
    const bool has_value = !o.args.empty();
    const double value = has_value ? argument(here, 0) : 0.0;
    // LinuxCNC: #<_value> is the returned value (0 without one), #<_value_returned> says which.
    parameters_.set("_value", value);
    parameters_.set("_value_returned", has_value ? 1.0 : 0.0);
    // M73's state comes back first (rs274ngc restores it at the return).
    interpreter_.leave_call(line_at(here).block.line, line_at(here).text);
    pc = frames_.back().return_to;
    frames_.pop_back();
    parameters_.return_from_call();
  }

  [[noreturn]] void fail_at_end() {
    if (!skipping_to_sub_.empty()) {
      const Place call = skip_start_;
      fail(call, fmt::format("call of an undefined subroutine {}", label_text(skipping_to_sub_)));
    }
    const OWord& o = line_at(skip_start_).block.o;
    const char* missing = "its end";
    switch (o.keyword) {
      case OKeyword::sub:
        missing = "endsub";
        break;
      case OKeyword::if_:
      case OKeyword::elseif:
      case OKeyword::else_:
        missing = "endif";
        break;
      case OKeyword::while_:
        missing = "endwhile";
        break;
      case OKeyword::repeat:
        missing = "endrepeat";
        break;
      default:
        break;
    }
    fail(skip_start_,
         fmt::format("{} without {} (the file ends while skipping to it)", what(o), missing));
  }

  void run_from(Place pc) {
    while (!interpreter_.program_ended()) {
      StoredLine* l = pc.source->at(pc.index);
      if (l == nullptr) {
        if (!skipping_.empty() || !skipping_to_sub_.empty()) fail_at_end();
        if (pc.source != &main_) fail(frames_.back().call, "the called subroutine has no endsub");
        return;
      }
      Block& b = l->block;
      if (b.o.keyword == OKeyword::none) {
        if (skipping_.empty() && skipping_to_sub_.empty()) execute(b, l->text, pc.source->file);
        ++pc.index;
        continue;
      }
      const OWord& o = b.o;
      // A definition is skipped up to its endsub; nothing in it runs.
      if (defining_sub_ && !(o.keyword == OKeyword::endsub && o.label == skipping_)) {
        ++pc.index;
        continue;
      }
      if (!skipping_.empty() && skipping_ != effective_label(o)) {
        ++pc.index;
        continue;
      }
      if (!skipping_to_sub_.empty() && o.keyword != OKeyword::sub) {
        ++pc.index;
        continue;
      }
      ++stats_.lines;
      control(pc, o);
    }
  }

  // rs274ngc: "return" and "endsub" belong to the subroutine they are in,
  // whatever label they carry (o1010 return inside o1000 sub is o1000's).
  const std::string& effective_label(const OWord& o) const {
    if ((o.keyword == OKeyword::return_ || o.keyword == OKeyword::endsub) && !frames_.empty())
      return line_at(frames_.back().call).block.o.label;
    return o.label;
  }

  // One O-word line that is not skipped (rs274ngc's convert_control_functions).
  void control(Place& pc, const OWord& o) {
    const Place here = pc;
    ++pc.index;
    switch (o.keyword) {
      case OKeyword::sub: {
        if (!skipping_.empty() || !skipping_to_sub_.empty()) {
          // Skipping to a sub: define it now.
          if (!skipping_to_sub_.empty() && skipping_to_sub_ != o.label) return;
          remember(here);
          skipping_.clear();
        }
        skipping_to_sub_.clear();
        if (!frames_.empty()) return;  // entering a called subroutine
        if (defining_sub_) fail(here, "a subroutine definition inside another one");
        if (Label* l = find(o.label);
            l != nullptr && !(l->at.source == here.source && l->at.index == here.index))
          fail(here, fmt::format("{} is defined twice (first in line {})", label_text(o.label),
                                 line_at(l->at).block.line));
        remember(here);
        skip_to(o.label, here);
        defining_sub_ = true;
        return;
      }
      case OKeyword::endsub:
      case OKeyword::return_: {
        if (frames_.empty()) {
          if (!defining_sub_) fail(here, fmt::format("{} outside a subroutine", what(o)));
          if (o.keyword == OKeyword::endsub) {  // end of a definition
            skipping_.clear();
            defining_sub_ = false;
          }
          return;
        }
        if (o.keyword == OKeyword::endsub && skipping_ == o.label) skipping_.clear();
        do_return(here, pc, o);
        return;
      }
      case OKeyword::call:
        call(here, pc);
        return;
      case OKeyword::do_:
        skipping_.clear();
        if (find(o.label) == nullptr) remember(here);
        return;
      case OKeyword::repeat: {
        remember_once(here, false);
        skipping_.clear();
        Label& l = *find(o.label);
        if (l.keyword != OKeyword::repeat) return;
        if (l.repeat_count == -1) {
          const double n = condition(here);
          l.repeat_count = std::lround(n);  // rs274ngc rounds the count
        }
        if (l.repeat_count > 0) {
          --l.repeat_count;
        } else {
          skip_to(o.label, here);
          l.repeat_count = -1;
        }
        return;
      }
      case OKeyword::while_: {
        remember_once(here, true);
        skipping_.clear();
        const Label& l = *find(o.label);
        const double test = condition(here);
        if (l.keyword == OKeyword::while_) {
          if (test == 0.0) skip_to(o.label, here);
        } else if (test != 0.0 && !doing_break_) {  // the end of a do
          count_iteration(here);
          back_to(o.label, pc);
        } else {
          doing_break_ = false;
        }
        return;
      }
      case OKeyword::if_: {
        remember_once(here, false);
        if (condition(here) != 0.0) {
          skipping_.clear();
          executed_if_ = true;
        } else {
          skip_to(o.label, here);
          executed_if_ = false;
        }
        return;
      }
      case OKeyword::elseif: {
        opened_by(here, {OKeyword::if_});
        const double test = condition(here);
        if (executed_if_) {
          skip_to(o.label, here);
        } else if (test != 0.0) {
          skipping_.clear();
          executed_if_ = true;
        }
        return;
      }
      case OKeyword::else_: {
        opened_by(here, {OKeyword::if_});
        if (executed_if_) {
          skip_to(o.label, here);
        } else if (skipping_ == o.label) {
          executed_if_ = true;
          skipping_.clear();
        }
        return;
      }
      case OKeyword::endif:
        opened_by(here, {OKeyword::if_});
        skipping_.clear();
        executed_if_ = true;
        return;
      case OKeyword::break_:
        opened_by(here, {OKeyword::while_, OKeyword::do_});
        skip_to(o.label, here);
        doing_break_ = true;
        return;
      case OKeyword::continue_:
        opened_by(here, {OKeyword::while_, OKeyword::do_});
        if (skipping_ == o.label) return;
        skip_to(o.label, here);
        doing_continue_ = true;
        return;
      case OKeyword::endwhile:
      case OKeyword::endrepeat: {
        opened_by(here, {o.keyword == OKeyword::endwhile ? OKeyword::while_ : OKeyword::repeat});
        if (skipping_ == o.label) {
          skipping_.clear();
          if (!doing_continue_) return;  // the loop is done
          doing_continue_ = false;
        }
        count_iteration(here);
        back_to(o.label, pc);
        return;
      }
      case OKeyword::none:
        return;
    }
  }

  const InterpreterConfig& config_;
  Interpreter interpreter_;
  const MotionSink& sink_;
  ProgramStats& stats_;
  std::size_t current_line_ = 0;  // line of the block being executed (#<_line>)
  ParameterStore parameters_;
  Source main_;
  std::vector<std::unique_ptr<Source>> sub_files_;
  std::map<std::string, Label> labels_;
  std::vector<Frame> frames_;
  std::string skipping_;         // skip to the next O-word line with this label
  std::string skipping_to_sub_;  // skip to "o<label> sub"
  Place skip_start_;             // the line that started the skip
  bool defining_sub_ = false;
  bool executed_if_ = false;
  bool doing_break_ = false;
  bool doing_continue_ = false;
  std::uint64_t iterations_ = 0;
};

}  // namespace

ProgramStats run_rs274_program(std::istream& in, const std::string& file,
                               const InterpreterConfig& config, const MotionSink& sink) {
  ProgramStats stats;
  Runner runner(file, config, sink, stats);
  runner.run(in, file);
  runner.finish();
  return stats;
}

}  // namespace abbe::gcode::detail
