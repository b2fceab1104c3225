#pragma once
// --table-uncertainty N of `abbe diagnose` and `abbe report diagnose`: the
// tables' uncertainty in every effect's u (diagnose/table_uncertainty.hpp,
// docs/diagnosis.md). Not given: the library's default (50 draws where the
// machine file gives an uncertainty); 0: the data's u alone.
#include <CLI/CLI.hpp>
#include <cstdint>

#include "abbe/diagnose/table_uncertainty.hpp"

namespace abbe::cli {

// Adds the option to `sub`; `draws` keeps −1 when it is not given.
void add_table_uncertainty_option(CLI::App& sub, long& draws);

// The library's options from the option's value and the draws' seed; an
// InputError (field --table-uncertainty) for 1 draw.
diagnose::TableUncertaintyOptions table_uncertainty_options(long draws, std::uint64_t seed);

}  // namespace abbe::cli
