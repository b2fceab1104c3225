#include "table_uncertainty_option.hpp"

#include "interpreter_options.hpp"

namespace abbe::cli {

void add_table_uncertainty_option(CLI::App& sub, long& draws) {
  sub.add_option("--table-uncertainty", draws,
                 "The tables' uncertainty (machine file `uncertainty`, table column "
                 "`uncertainty`) in every effect's u by Monte Carlo with N draws of the campaign, "
                 "the effects refitted in each; the report gives the data's and the tables' parts "
                 "(docs/diagnosis.md). Default: 50 draws where the machine file gives an "
                 "uncertainty; 0: the data's u alone")
      ->check(CLI::Range(0L, 100000L));
}

diagnose::TableUncertaintyOptions table_uncertainty_options(long draws, std::uint64_t seed) {
  if (draws == 1)
    bad_option("--table-uncertainty",
               "--table-uncertainty needs at least 2 draws (0: the data's u alone)");
  diagnose::TableUncertaintyOptions o;
  if (draws >= 0) o.draws = static_cast<std::size_t>(draws);
  o.seed = seed;
  return o;
}

}  // namespace abbe::cli
