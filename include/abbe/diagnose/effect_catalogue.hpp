#pragma once
// The effect catalogue: one registered descriptor per kind of diagnosis term
// (DESIGN.md §5 kinds plus `unexplained`) holding everything the kind knows
// about itself — its basis functions, labels and plain-language description,
// its named parameters, and the kind-specific fields of its overlay entry.
// Term, the overlay reader and writer, the diagnosis and its report all go
// through it; a new kind is one file with its descriptor and one
// register_effect call (docs/effect-catalogue.md).
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "abbe/diagnose/term.hpp"

namespace abbe::diagnose {

using BasisOut = Eigen::Ref<Eigen::Matrix<double, 3, Eigen::Dynamic>>;
using NamedValues = std::vector<std::pair<std::string, double>>;

// The fields of one overlay entry, as a descriptor reads them. Every reader
// fails with an abbe::InputError naming the overlay file, the line and column
// of the value (or of the entry when the key is missing) and the key.
class OverlayFields {
 public:
  virtual ~OverlayFields() = default;
  virtual bool has(const char* key) const = 0;
  // Required values ("a <term> effect needs `<key>`" when missing):
  virtual int axis(const char* key) const = 0;  // X, Y or Z
  virtual double number(const char* key) const = 0;
  virtual std::vector<double> numbers(const char* key) const = 0;
  virtual std::string text(const char* key) const = 0;
  virtual std::vector<std::string> texts(const char* key) const = 0;  // a list
  // Fails at the value of `key` (at the entry when it is missing)…
  [[noreturn]] virtual void fail(const char* key, const std::string& message) const = 0;
  // …at the entry itself, naming `key`…
  [[noreturn]] virtual void fail_entry(const char* key, const std::string& message) const = 0;
  // …or at item `index` of the list under `key`.
  [[noreturn]] virtual void fail_item(const char* key, std::size_t index,
                                      const std::string& message) const = 0;
};

struct EffectDescriptor {
  TermKind kind = TermKind::scale;
  std::string id;         // catalogue id (DESIGN.md §5): "setup" for both setup terms
  std::string term_name;  // overlay `term:` value, unique ("setup_offset")
  // Common overlay fields: `axis:` read and written, `direction:` read
  // (written whenever set), axis taken from the direction.
  bool reads_axis = true;
  bool writes_axis = true;
  bool reads_direction = true;
  bool axis_is_direction = false;
  // Outside the domain an overlay was fitted on (overlay_domain.hpp): true
  // for kinds evaluated there as written (linear geometric terms, bounded
  // ones); false (the default: polynomial, smooth and time terms) clamps
  // the term's arguments to the domain instead of extrapolating.
  bool extrapolates = false;

  int (*columns)(const Term& t) = nullptr;  // null: one column
  // g_c(point) for every column c (out is zeroed before).
  void (*basis)(const Term& t, const PointContext& pc, BasisOut out) = nullptr;
  std::string (*label)(const Term& t) = nullptr;        // e.g. "reversal Y→Y"
  std::string (*description)(const Term& t) = nullptr;  // one line with the numbers
  NamedValues (*params)(const Term& t) = nullptr;       // values for the report
  // Standard errors of params; null: the first parameter's, from column 0.
  NamedValues (*param_stderr)(const Term& t) = nullptr;
  // The kind's own overlay fields (null: none). read_fields runs after the
  // common fields; write_fields appends "    key: value\n" lines.
  void (*read_fields)(Term& t, const OverlayFields& in) = nullptr;
  void (*write_fields)(const Term& t, std::string& yaml) = nullptr;
};

// A descriptor with its kind, catalogue id and overlay term name (the
// formulas and flags to be filled in).
EffectDescriptor make_descriptor(TermKind kind, std::string id, std::string term_name);

// Every registered kind: the built-in ones in DESIGN.md's order, then the
// registered ones in the order of registration.
const std::vector<EffectDescriptor>& effect_catalogue();

// Throws std::invalid_argument for a kind nobody registered.
const EffectDescriptor& effect_descriptor(TermKind kind);

// The kind whose term_name is `name`; null when there is none.
const EffectDescriptor* find_effect(std::string_view term_name);

// Adds a kind (its value ≥ kFirstRegisteredKind). Throws
// std::invalid_argument for a taken kind or term name, or a missing basis,
// label, description or params. Not thread-safe: register at start-up.
constexpr int kFirstRegisteredKind = 100;
void register_effect(EffectDescriptor descriptor);

}  // namespace abbe::diagnose
