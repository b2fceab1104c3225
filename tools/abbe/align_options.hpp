#pragma once
// The part's set-up options of predict, report predict and compensate: --align
// none|best-fit|datums and the three datum sets --datum-primary,
// --datum-secondary, --datum-tertiary (source lines, docs/models.md, "The
// part").
#include <CLI/CLI.hpp>
#include <string>

#include "abbe/pipeline/aligned_prediction.hpp"

namespace abbe::cli {

struct AlignCliOptions {
  std::string align = "none";
  std::string datum[3];  // --datum-primary/secondary/tertiary: source lines
};

// `align_help`: what --align does in the command (default: predict's text).
void add_align_options(CLI::App& sub, AlignCliOptions& o, const char* align_help = nullptr);

// The alignment the options ask for; false after a message on stderr
// ("abbe COMMAND: …", a usage error) when --align datums lacks a datum set
// or a datum set is given without --align datums. Throws abbe::InputError
// naming the option for a bad line set.
bool align_options(const AlignCliOptions& o, const char* command, pipeline::AlignOptions& ao);

}  // namespace abbe::cli
