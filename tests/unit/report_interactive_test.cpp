// The interactive and bounded parts of the reports: the inputs' digests, the footer, the colour-blind-safe palette,
// the 3-D toolpath's data and the ISO 230-2 report.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "abbe/diagnose/iso230.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/iso230_section.hpp"
#include "abbe/io/sha256.hpp"
#include "abbe/report/palette.hpp"
#include "abbe/report/svg.hpp"
#include "abbe/report/toolpath_view.hpp"

namespace abbe::report {
namespace {

TEST(ReportFooter, InputDigestIsTheFilesSha256) {
  const std::string path = std::string(ABBE_TEST_DATA_DIR) + "/iso230/hand.csv";
  std::ifstream f(path, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
  EXPECT_EQ(io::sha256_file(path), io::sha256_hex(text));
  EXPECT_THROW(io::sha256_file("/nonexistent/file.ngc"), std::exception);
}

TEST(ReportFooter, DateVersionCommandLineAndHashes) {
  ::setenv("SOURCE_DATE_EPOCH", "1764104400", 1);  // 2025-11-25T21:00:00Z
  EXPECT_EQ(report_date(), "2025-11-25T21:00:00Z");
  HtmlPage page("t");
  Provenance p;
  p.command_line = "abbe report predict 'a b.ngc' --machine <m>.yaml";
  p.inputs = {{"a b.ngc", io::sha256_hex("abc")}};
  page.set_provenance(p);
  const std::string html = page.render();
  ::unsetenv("SOURCE_DATE_EPOCH");
  EXPECT_NE(html.find("made 2025-11-25T21:00:00Z by abbe " ABBE_VERSION), std::string::npos);
  EXPECT_NE(html.find("abbe report predict &#39;a b.ngc&#39; --machine &lt;m&gt;.yaml"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("input a b.ngc: SHA-256 <code>ba7816bf8f01cfea414140de5dae2223b00361a39617"
                      "7a9cb410ff61f20015ad</code>"),
            std::string::npos);
}

// "#rrggbb" → r, g, b.
std::array<int, 3> rgb(const std::string& c) {
  return {std::stoi(c.substr(1, 2), nullptr, 16), std::stoi(c.substr(3, 2), nullptr, 16),
          std::stoi(c.substr(5, 2), nullptr, 16)};
}

bool greenish(const std::string& c) {
  const auto v = rgb(c);
  return v[1] > v[0] + 30 && v[1] > v[2] + 30;
}
bool reddish(const std::string& c) {
  const auto v = rgb(c);
  return v[0] > v[1] + 100 && v[0] > v[2] + 100 && v[1] < 80;
}

TEST(ReportPalette, NoRedGreenPairs) {
  for (std::size_t i = 0; i < 8; ++i) EXPECT_FALSE(greenish(series_colour(i))) << i;
  for (auto k : {model::ModelKind::htm, model::ModelKind::ae_arm, model::ModelKind::dual}) {
    EXPECT_FALSE(greenish(palette::model_colour(k)));
    EXPECT_FALSE(reddish(palette::model_colour(k)));
  }
  EXPECT_NE(palette::model_colour(model::ModelKind::htm),
            palette::model_colour(model::ModelKind::ae_arm));
  EXPECT_NE(palette::model_colour(model::ModelKind::ae_arm),
            palette::model_colour(model::ModelKind::dual));
  // Within the tolerance blue (b the largest channel, darker with |d|),
  // above it orange to brown (r the largest).
  int last_sum = 3 * 255 + 1;
  for (double r = 0.0; r <= 1.0; r += 0.125) {
    const auto v = rgb(palette::tolerance_colour(r));
    EXPECT_GE(v[2], v[0]);
    EXPECT_GE(v[2], v[1]);
    EXPECT_LT(v[0] + v[1] + v[2], last_sum);
    last_sum = v[0] + v[1] + v[2];
  }
  for (double r : {1.01, 1.5, 2.0, 3.0, 100.0}) {
    const auto v = rgb(palette::tolerance_colour(r));
    EXPECT_GT(v[0], v[2]) << r;
    EXPECT_FALSE(greenish(palette::tolerance_colour(r)));
  }
  EXPECT_EQ(palette::tolerance_colour(std::nan("")), "#999999");
}

PredictedPath two_point_path() {
  PredictedPath r;
  r.program = "p.ngc";
  r.models = {model::ModelKind::ae_arm};
  r.nominal = {{0, 0, 0}, {10.5, -2.25, 1.0}};
  r.line = {3, 4};
  r.index = {0, 1};
  r.path_length = {0.0, 10.8};
  r.deviation_um = {{{1.0, 2.0, 2.0}, {0.0, 0.0, std::nan("")}}};
  ModelPathStats s;
  s.max_um = 3.0;
  r.stats = {s};
  r.source = {{3, "G1 X0 (</script><b>)"}, {4, "G1 X10.5"}};
  return r;
}

TEST(ReportToolpathView, JsonHoldsEveryPointAndEscapesText) {
  const PredictedPath r = two_point_path();
  ToolpathViewOptions o;
  o.exaggerate = 500.0;
  o.tolerance_um = 2.5;
  const std::string j = toolpath_view_json(r, o);
  EXPECT_EQ(j,
            "{\"k\":500,\"tol\":2.5,\"models\":[\"ae-arm\"],\"p\":[0,0,0,10.5,-2.25,1],"
            "\"line\":[3,4],\"d\":[[1,2,2,0,0,null]],\"src\":{\"3\":\"G1 X0 (\\u003c/script>"
            "\\u003cb>)\",\"4\":\"G1 X10.5\"}}");
  // Automatic tolerance: the largest max |d| rounded up to two digits.
  EXPECT_NEAR(auto_tolerance(r), 3.0, 1e-12);
  PredictedPath big = r;
  big.stats[0].max_um = 44.37;
  EXPECT_NEAR(auto_tolerance(big), 45.0, 1e-12);
  big.stats[0].max_um = 0.1234;
  EXPECT_NEAR(auto_tolerance(big), 0.13, 1e-12);
  big.stats[0].max_um = 0.0;
  EXPECT_DOUBLE_EQ(auto_tolerance(big), 1.0);
  const std::string html = render_toolpath_view(r, o);
  EXPECT_EQ(html.find("</script><b>"), std::string::npos);
  EXPECT_NE(html.find("id=\"toolpath-3d-tol\" min=\"0\" step=\"any\" value=\"2.5\""),
            std::string::npos);
  EXPECT_NE(html.find("<option>ae-arm</option>"), std::string::npos);
}

TEST(ReportIso230, ChartAndTableFromTheEvaluation) {
  const std::string path = std::string(ABBE_TEST_DATA_DIR) + "/iso230/hand.csv";
  std::ifstream f(path);
  const auto results = diagnose::evaluate_iso230(diagnose::read_iso230_runs(f, path), path);
  ASSERT_FALSE(results.empty());
  HtmlPage page("iso");
  render_iso230_report(page, results);
  const std::string html = page.render();
  EXPECT_NE(html.find("id=\"iso230-table\""), std::string::npos);
  for (const auto& r : results) {
    std::string id = std::string("iso230-") + static_cast<char>(std::tolower(r.axis)) + "-";
    for (char c : r.component) id += static_cast<char>(std::tolower(c));
    EXPECT_NE(html.find("id=\"" + id + "\""), std::string::npos) << id;
    EXPECT_NE(html.find(fmt::format("<td>{}</td><td>{}</td>", r.axis, r.component)),
              std::string::npos);
    if (std::isfinite(r.A)) {
      EXPECT_NE(html.find(fmt::format("<td>{:.3f}</td>", r.A)), std::string::npos);
    }
    // The hover text of every target's mean, per direction.
    for (const auto& t : r.targets) {
      if (r.has_up) {
        EXPECT_NE(html.find(fmt::format("target {:g} mm, up: x̄↑ = {:.3f}", t.target_mm, t.mean_up)),
                  std::string::npos);
      }
    }
  }
  EXPECT_NE(html.find("x̄↑ ± 2s↑"), std::string::npos);
  EXPECT_FALSE(std::regex_search(html, std::regex("\\bnan\\b|\\binf\\b", std::regex::icase)));
}

}  // namespace
}  // namespace abbe::report
