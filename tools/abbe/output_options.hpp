#pragma once
// The output convention of every abbe command (README, "A short tour"):
//  - `-o FILE` writes the command's data (atomically), `-o -` to stdout;
//  - `--format csv|json` (or text|json) where both make sense;
//  - the human summary goes to stderr whenever the data go to stdout, so
//    `abbe map -o - | …` gets clean CSV.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

namespace abbe::cli {

// Adds -o,--output FILE ("-" = stdout) bound to `output`.
CLI::Option* add_output_option(CLI::App& sub, std::string& output, const std::string& what);

// Adds --format bound to `format`, one of `choices` (the first is the default
// when `format` is empty).
CLI::Option* add_format_option(CLI::App& sub, std::string& format,
                               const std::vector<std::string>& choices);

// A hidden alias of an option kept for old command lines and scripts
// (not shown in --help).
CLI::Option* add_hidden_alias(CLI::App& sub, const std::string& name, std::string& target);

// stderr when the data go to stdout (`output` is "-"), else stdout.
std::FILE* summary_stream(const std::string& output);

}  // namespace abbe::cli
