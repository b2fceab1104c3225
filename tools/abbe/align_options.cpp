#include "align_options.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace abbe::cli {
namespace {

const char* const kDatumOption[3] = {"--datum-primary", "--datum-secondary", "--datum-tertiary"};

}  // namespace

void add_align_options(CLI::App& sub, AlignCliOptions& o, const char* align_help) {
  sub.add_option("--align", o.align,
                 align_help ? align_help
                            : "Also report the deviation after the part's set-up: best-fit (least "
                              "squares over the cutting points) or datums (3-2-1, --datum-*)")
      ->check(CLI::IsMember({"none", "best-fit", "datums"}))
      ->capture_default_str();
  sub.add_option("--datum-primary", o.datum[0],
                 "--align datums: source lines of the primary (plane) points, e.g. 12-30,45");
  sub.add_option("--datum-secondary", o.datum[1],
                 "--align datums: source lines of the secondary (line) points");
  sub.add_option("--datum-tertiary", o.datum[2],
                 "--align datums: source lines of the tertiary (point) points");
}

bool align_options(const AlignCliOptions& o, const char* command, pipeline::AlignOptions& ao) {
  for (int k = 0; k < 3; ++k)
    if (!o.datum[k].empty() && o.align != "datums") {
      fmt::print(stderr, "abbe {}: {} needs --align datums\n", command, kDatumOption[k]);
      return false;
    }
  ao.method = pipeline::parse_align_method(o.align);
  if (ao.method != pipeline::AlignMethod::datums) return true;
  for (int k = 0; k < 3; ++k)
    if (o.datum[k].empty()) {
      fmt::print(stderr, "abbe {}: --align datums needs {}\n", command, kDatumOption[k]);
      return false;
    }
  ao.primary = pipeline::LineSet::parse(o.datum[0], kDatumOption[0]);
  ao.secondary = pipeline::LineSet::parse(o.datum[1], kDatumOption[1]);
  ao.tertiary = pipeline::LineSet::parse(o.datum[2], kDatumOption[2]);
  return true;
}

}  // namespace abbe::cli
