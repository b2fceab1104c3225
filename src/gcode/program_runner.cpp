// Parameters, expressions and O-word control flow of RS274/NGC, as
// LinuxCNC's rs274ngc executes them, between the BlockReader and the
// Interpreter:
// - a block's words are evaluated first, then its parameter settings take
//   effect (all reads of a line see the values from before the line), then
//   the interpreter executes it;
// - plain lines stream through; from the first O-word on, the lines read are
//   kept (text and parsed block) so that loops and calls can go back;
// - sub ... endsub is skipped where it stands and remembered; a call of a
//   subroutine not seen yet looks ahead in the file, then for name.ngc in
//   the subroutine folder;
// - if/elseif/else/endif, while/endwhile, do/while, repeat/endrepeat,
//   break/continue are matched by their label, as in rs274ngc;
// - loops are bounded (DialectOptions::loop_limit iterations in all) and
//   calls nest at most kMaxCallDepth deep.
#include "program_runner.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <map>
#include <optional>
#include <memory>
#include <vector>

#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"
#include "expression_eval.hpp"
#include "parameters.hpp"

namespace abbe::gcode::detail {

namespace {

constexpr std::size_t kMaxCallDepth = 10;  // rs274ngc's subroutine levels

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

enum class LoopKind { while_loop, do_loop, repeat_loop };

struct Loop {
  LoopKind kind;
  std::string label;
  Place start;  // the while / do / repeat line
  double remaining = 0.0;  // repeat
  std::size_t ifs = 0;     // open ifs when the loop began (break/continue leave the rest)
};

struct Frame {
  Place return_to;
  std::size_t loops = 0;  // loop stack size at the call
  std::size_t ifs = 0;
  std::string label;
};

struct If {
  std::string label;
  Place start;
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
    if (!config.dialect.var_file.empty()) parameters_.read_var_file(config.dialect.var_file);
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
  CodeSite site(const Block& b, std::string_view text, const std::string& file) const {
    return CodeSite{file, b.line, text};
  }

  void execute(Block& block, std::string_view text, const std::string& file) {
    ++stats_.lines;
    if (block.has_code()) {
      const CodeSite s = site(block, text, file);
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
    interpreter_.execute_evaluated(block, text, counting_sink_);
  }

  [[noreturn]] void fail(const Place& at, std::uint32_t column, const std::string& message) {
    const StoredLine& l = *at.source->lines[at.index];
    fail_at(CodeSite{at.source->file, l.block.line, l.text}, column, message);
  }

  double argument(const Place& at, std::size_t i) {
    StoredLine& l = *at.source->lines[at.index];
    return evaluate(l.block, l.block.o.args[i], parameters_,
                    CodeSite{at.source->file, l.block.line, l.text});
  }

  void need_arguments(const Place& at, std::size_t n) {
    const OWord& o = at.source->lines[at.index]->block.o;
    if (o.args.size() != n)
      fail(at, o.keyword_column,
           fmt::format("o{} {} needs {} [...] argument{}", label_text(o.label),
                       o_keyword_name(o.keyword), n == 1 ? "one" : "no", n == 1 ? "" : "s"));
  }

  static std::string label_text(const std::string& label) {
    return (!label.empty() && label[0] >= '0' && label[0] <= '9') ? label : "<" + label + ">";
  }

  // The next line after `from` in the same source with this label and one of
  // the keywords; an error naming the opening line if there is none.
  Place find_forward(const Place& from, const std::string& label,
                     std::initializer_list<OKeyword> keywords, const char* missing) {
    for (std::size_t i = from.index + 1;; ++i) {
      StoredLine* l = from.source->at(i);
      if (l == nullptr) {
        const OWord& o = from.source->lines[from.index]->block.o;
        fail(from, o.column,
             fmt::format("o{} {} without {}", label_text(label), o_keyword_name(o.keyword), missing));
      }
      if (l->block.o.keyword != OKeyword::none && l->block.o.label == label)
        for (OKeyword k : keywords)
          if (l->block.o.keyword == k) return Place{from.source, i};
    }
  }

  void count_iteration(const Place& at) {
    if (++iterations_ > config_.dialect.loop_limit) {
      const OWord& o = at.source->lines[at.index]->block.o;
      fail(at, o.column,
           fmt::format("more than {} loop iterations (o{} {}): a runaway loop? (the limit is "
                       "--loop-limit)",
                       config_.dialect.loop_limit, label_text(o.label), o_keyword_name(o.keyword)));
    }
  }

  // A subroutine's "o<label> sub" line: seen before, later in the file, or in
  // the subroutine folder.
  Place find_sub(const Place& call) {
    const std::string& label = call.source->lines[call.index]->block.o.label;
    if (auto it = subs_.find(label); it != subs_.end()) return it->second;
    for (std::size_t i = call.index + 1;; ++i) {
      StoredLine* l = call.source->at(i);
      if (l == nullptr) break;
      if (l->block.o.keyword == OKeyword::sub && l->block.o.label == label)
        return subs_[label] = Place{call.source, i};
    }
    if (&*call.source != &main_)  // a sub file may call subs of the main file
      for (std::size_t i = 0;; ++i) {
        StoredLine* l = main_.at(i);
        if (l == nullptr) break;
        if (l->block.o.keyword == OKeyword::sub && l->block.o.label == label)
          return subs_[label] = Place{&main_, i};
      }
    if (!config_.dialect.subroutine_path.empty()) {
      const std::string path = config_.dialect.subroutine_path + "/" + label + ".ngc";
      std::ifstream in(path);
      if (in) {
        auto source = std::make_unique<Source>();
        source->file = path;
        BlockReader reader(in, path);
        source->reader = &reader;
        for (std::size_t i = 0; source->at(i) != nullptr; ++i) {
        }
        source->reader = nullptr;
        sub_files_.push_back(std::move(source));
        Source* s = sub_files_.back().get();
        for (std::size_t i = 0; i < s->lines.size(); ++i)
          if (s->lines[i]->block.o.keyword == OKeyword::sub && s->lines[i]->block.o.label == label)
            return subs_[label] = Place{s, i};
      }
    }
    const OWord& o = call.source->lines[call.index]->block.o;
    fail(call, o.column, fmt::format("call of an undefined subroutine o{}", label_text(label)));
  }

  void do_return(Place& pc, double value, bool has_value) {
    // LinuxCNC: #<_value> is the returned value (0 without one), #<_value_returned> says which.
    parameters_.set("_value", has_value ? value : 0.0);
    parameters_.set("_value_returned", has_value ? 1.0 : 0.0);
    const Frame f = frames_.back();
    frames_.pop_back();
    loops_.resize(f.loops);
    ifs_.resize(f.ifs);
    parameters_.return_from_call();
    pc = f.return_to;
  }

  void run_from(Place pc) {
    while (!interpreter_.program_ended()) {
      StoredLine* l = pc.source->at(pc.index);
      if (l == nullptr) {
        if (!ifs_.empty()) {
          const Place at = ifs_.back().start;
          fail(at, at.source->lines[at.index]->block.o.column,
               fmt::format("o{} if without endif", label_text(ifs_.back().label)));
        }
        if (!loops_.empty()) {
          const Place at = loops_.back().start;
          fail(at, at.source->lines[at.index]->block.o.column,
               fmt::format("o{} loop without its end", label_text(loops_.back().label)));
        }
        if (!frames_.empty()) {
          const Place call{frames_.back().return_to.source, frames_.back().return_to.index - 1};
          fail(call, call.source->lines[call.index]->block.o.column,
               "the subroutine called here ends without endsub");
        }
        return;
      }
      Block& b = l->block;
      if (b.o.keyword == OKeyword::none) {
        if (pc.source != &main_ && frames_.empty()) return;  // cannot happen
        execute(b, l->text, pc.source->file);
        ++pc.index;
        continue;
      }
      ++stats_.lines;
      const OWord& o = b.o;
      switch (o.keyword) {
        case OKeyword::sub: {
          subs_[o.label] = pc;
          pc = find_forward(pc, o.label, {OKeyword::endsub}, "endsub");
          ++pc.index;
          break;
        }
        case OKeyword::endsub:
        case OKeyword::return_: {
          // rs274ngc: a return may carry any label (that of an enclosing
          // if, say); endsub must carry its subroutine's.
          if (frames_.empty() ||
              (o.keyword == OKeyword::endsub && frames_.back().label != o.label))
            fail(pc, o.column,
                 fmt::format("o{} {} outside its subroutine", label_text(o.label),
                             o_keyword_name(o.keyword)));
          const bool has_value = !o.args.empty();
          const double value = has_value ? argument(pc, 0) : 0.0;
          do_return(pc, value, has_value);
          break;
        }
        case OKeyword::call: {
          if (frames_.size() >= kMaxCallDepth)
            fail(pc, o.column,
                 fmt::format("subroutine calls nested more than {} deep", kMaxCallDepth));
          std::vector<double> args;
          for (std::size_t i = 0; i < o.args.size(); ++i) args.push_back(argument(pc, i));
          if (args.size() > static_cast<std::size_t>(ParameterStore::kCallArguments))
            fail(pc, o.column, "more than 30 arguments in a call");
          const Place sub = find_sub(pc);
          frames_.push_back(Frame{Place{pc.source, pc.index + 1}, loops_.size(), ifs_.size(), o.label});
          parameters_.enter_call(args);
          pc = Place{sub.source, sub.index + 1};
          break;
        }
        case OKeyword::if_: {
          need_arguments(pc, 1);
          ifs_.push_back(If{o.label, pc});
          Place at = pc;
          while (argument(at, 0) == 0.0) {
            at = find_forward(pc, o.label, {OKeyword::elseif, OKeyword::else_, OKeyword::endif},
                              "endif");
            pc = at;
            const OKeyword k = at.source->lines[at.index]->block.o.keyword;
            if (k != OKeyword::elseif) break;
            need_arguments(at, 1);
          }
          if (at.source->lines[at.index]->block.o.keyword == OKeyword::endif) ifs_.pop_back();
          pc = Place{at.source, at.index + 1};
          break;
        }
        case OKeyword::elseif:
        case OKeyword::else_: {
          if (ifs_.empty() || ifs_.back().label != o.label)
            fail(pc, o.column,
                 fmt::format("o{} {} without if", label_text(o.label), o_keyword_name(o.keyword)));
          pc = find_forward(pc, o.label, {OKeyword::endif}, "endif");
          ifs_.pop_back();
          ++pc.index;
          break;
        }
        case OKeyword::endif: {
          if (ifs_.empty() || ifs_.back().label != o.label)
            fail(pc, o.column, fmt::format("o{} endif without if", label_text(o.label)));
          ifs_.pop_back();
          ++pc.index;
          break;
        }
        case OKeyword::do_: {
          loops_.push_back(Loop{LoopKind::do_loop, o.label, pc, 0.0, ifs_.size()});
          ++pc.index;
          break;
        }
        case OKeyword::while_: {
          need_arguments(pc, 1);
          const bool ends_do = !loops_.empty() && loops_.back().label == o.label &&
                               loops_.back().kind == LoopKind::do_loop;
          if (ends_do) {
            if (argument(pc, 0) != 0.0) {
              count_iteration(pc);
              pc = Place{loops_.back().start.source, loops_.back().start.index + 1};
            } else {
              loops_.pop_back();
              ++pc.index;
            }
            break;
          }
          const bool again = !loops_.empty() && loops_.back().label == o.label &&
                             loops_.back().start.source == pc.source &&
                             loops_.back().start.index == pc.index;
          if (argument(pc, 0) != 0.0) {
            if (again)
              count_iteration(pc);
            else
              loops_.push_back(Loop{LoopKind::while_loop, o.label, pc, 0.0, ifs_.size()});
            ++pc.index;
          } else {
            if (again) loops_.pop_back();
            pc = find_forward(pc, o.label, {OKeyword::endwhile}, "endwhile");
            ++pc.index;
          }
          break;
        }
        case OKeyword::endwhile: {
          if (loops_.empty() || loops_.back().label != o.label ||
              loops_.back().kind != LoopKind::while_loop)
            fail(pc, o.column, fmt::format("o{} endwhile without while", label_text(o.label)));
          pc = loops_.back().start;
          break;
        }
        case OKeyword::repeat: {
          need_arguments(pc, 1);
          const double n = argument(pc, 0);
          if (n >= 1.0) {
            loops_.push_back(Loop{LoopKind::repeat_loop, o.label, pc, std::floor(n), ifs_.size()});
            ++pc.index;
          } else {
            pc = find_forward(pc, o.label, {OKeyword::endrepeat}, "endrepeat");
            ++pc.index;
          }
          break;
        }
        case OKeyword::endrepeat: {
          if (loops_.empty() || loops_.back().label != o.label ||
              loops_.back().kind != LoopKind::repeat_loop)
            fail(pc, o.column, fmt::format("o{} endrepeat without repeat", label_text(o.label)));
          Loop& loop = loops_.back();
          loop.remaining -= 1.0;
          if (loop.remaining >= 1.0) {
            count_iteration(pc);
            pc = Place{loop.start.source, loop.start.index + 1};
          } else {
            loops_.pop_back();
            ++pc.index;
          }
          break;
        }
        case OKeyword::break_:
        case OKeyword::continue_: {
          std::size_t k = loops_.size();
          const std::size_t floor = frames_.empty() ? 0 : frames_.back().loops;
          while (k > floor && loops_[k - 1].label != o.label) --k;
          if (k == floor)
            fail(pc, o.column,
                 fmt::format("o{} {} outside its loop", label_text(o.label),
                             o_keyword_name(o.keyword)));
          loops_.resize(k);
          const Loop loop = loops_.back();
          ifs_.resize(loop.ifs);
          const OKeyword end = loop.kind == LoopKind::while_loop    ? OKeyword::endwhile
                               : loop.kind == LoopKind::repeat_loop ? OKeyword::endrepeat
                                                                     : OKeyword::while_;
          const Place close = find_forward(loop.start, o.label, {end}, o_keyword_name(end));
          if (o.keyword == OKeyword::break_) {
            loops_.pop_back();
            pc = Place{close.source, close.index + 1};
          } else {
            pc = close;  // the closing line decides whether the loop goes on
          }
          break;
        }
        case OKeyword::none:
          break;
      }
    }
  }

  const InterpreterConfig& config_;
  Interpreter interpreter_;
  const MotionSink& sink_;
  ProgramStats& stats_;
  MotionSink counting_sink_ = [this](const Motion& m) {
    ++stats_.motions;
    sink_(m);
  };
  ParameterStore parameters_;
  Source main_;
  std::vector<std::unique_ptr<Source>> sub_files_;
  std::map<std::string, Place> subs_;
  std::vector<Loop> loops_;
  std::vector<If> ifs_;
  std::vector<Frame> frames_;
  std::uint64_t iterations_ = 0;
};

}  // namespace

ProgramStats run_rs274_program(std::istream& in, const std::string& file,
                               const InterpreterConfig& config, const MotionSink& sink) {
  ProgramStats stats;
  Runner runner(file, config, sink, stats);
  runner.run(in, file);
  return stats;
}

}  // namespace abbe::gcode::detail
