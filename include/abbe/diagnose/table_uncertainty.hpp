#pragma once
// The tables' uncertainty in the diagnosis (docs/diagnosis.md, "The
// tables' uncertainty"). The effects are fitted to measured − predicted,
// and the prediction rests on a laser campaign's tables, which carry their
// own uncertainty (the machine file's `uncertainty` key, the table's
// `uncertainty` column). A table error is the same at every repetition of a
// point, so where it correlates with an effect's columns (a drift in time on
// a serpentine, whose time follows the position) it moves the effect, and
// the data's u (white noise about the fit) cannot show it.
//
// Monte Carlo (GUM Supplement 1): N seeded draws of the campaign
// (machine::draw_campaign); in each the residual is built again and the
// datum and named effects are refitted, their τ and periods linearised
// (Gauss–Newton, as searched_uncertainty.hpp). The standard deviation over
// the draws is each parameter's u from the tables; stderr_ and
// searched_stderr become √(u_data² + u_tables²), so that "an effect whose
// uncertainty exceeds its value is not named" counts both.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/selection.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::diagnose {

// Draws where the machine file gives an uncertainty and none were asked for.
inline constexpr std::size_t kDefaultTableDraws = 50;

struct TableUncertaintyOptions {
  // Monte Carlo draws: 0 not propagated, else at least 2; unset:
  // kDefaultTableDraws where the machine file gives an uncertainty, else 0.
  std::optional<std::size_t> draws;
  std::uint64_t seed = 1;
};

struct TableUncertainty {
  bool available = false;  // the machine file gives an uncertainty
  std::size_t draws = 0;   // 0: not propagated
  std::uint64_t seed = 1;
  std::string sources;  // machine::campaign_uncertainty_text
};

// Adds the tables' part to the uncertainties of `datum` and `effects`, the
// diagnosis of `data` against `machine` with `model`: `fitted` is its
// residual problem without the points `dropped` (sorted), those left out
// of the fit (without_points). SelectedTerm::stderr_data,
// stderr_tables, searched_stderr_data and searched_stderr_tables are set and
// the terms' stderr_ and searched_stderr combined. Smooth (`unexplained`)
// functions are not refitted (they are no names). Throws abbe::InputError
// (field `uncertainty` of the machine file) when the machine gives no
// uncertainty, std::invalid_argument for fewer than 2 draws.
TableUncertainty add_table_uncertainty(const machine::Machine& machine,
                                       const io::MeasuredData& data, model::ModelKind model,
                                       const Problem& fitted,
                                       const std::vector<std::uint32_t>& dropped, std::size_t draws,
                                       std::uint64_t seed, std::vector<SelectedTerm>& datum,
                                       std::vector<SelectedTerm>& effects);

}  // namespace abbe::diagnose
