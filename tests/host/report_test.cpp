// Tests of the HTML report (host/report): every section and figure is present, the page is
// self-contained (no script, nothing fetched), the paper's numbers stand beside ours on the
// paper scenario, text is escaped, and measured square runs bring their rows and figure.
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "host/report/gnuplot_svg.h"
#include "host/report/html_report.h"
#include "host/report/report_tables.h"
#include "tests/host/validation_test_helpers.h"

namespace h4::host {
namespace {

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Report, HoldsEverySectionAndFigureAndIsSelfContained) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const ValidationInputs in = PaperValidationInputs();
  const ValidationReport report = Validate(in);
  const std::string html = FormatHtmlReport(in, report, "h4cal report --sim-dir x");
  for (const char* id : kReportSections) {
    EXPECT_NE(html.find(std::string("<section id=\"") + id + "\">"), std::string::npos) << id;
  }
  // Accuracy map, residuals, histograms, straightness, square.
  EXPECT_EQ(Count(html, "<svg"), 5);
  EXPECT_EQ(Count(html, "Not computed"), 0);
  EXPECT_EQ(Count(html, "<script"), 0);
  EXPECT_FALSE(std::regex_search(html, std::regex("(src|href)=\"https?:")));
  EXPECT_EQ(html.find("nan"), std::string::npos);
}

TEST(Report, PaperScenarioShowsThePublishedNumbersBesideOurs) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const ValidationInputs in = PaperValidationInputs();
  const std::string html = FormatHtmlReport(in, Validate(in), "test");
  EXPECT_NE(html.find("before calibration (paper)"), std::string::npos);
  EXPECT_NE(html.find("after Model 12 (paper)"), std::string::npos);
  EXPECT_NE(html.find("identified (paper)"), std::string::npos);
  EXPECT_NE(html.find("1.3e-03"), std::string::npos) << "Table 4 before, direction 1";
  EXPECT_NE(html.find("9.0e-02"), std::string::npos) << "Table 3 before, joint 1";
}

// A result written before parameter_covariance has no accuracy map: the section says so,
// the notes say why, and no map file is written.
TEST(Report, AResultWithoutCovarianceHasNoAccuracyMapAndSaysWhy) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  ValidationInputs in = PaperValidationInputs();
  in.result12->parameter_covariance.reset();
  const ValidationReport report = Validate(in);
  EXPECT_FALSE(report.models.back().accuracy_map.has_value());
  const std::string html = FormatHtmlReport(in, report, "test");
  const size_t map = html.find("<section id=\"accuracy-map\">");
  ASSERT_NE(map, std::string::npos);
  EXPECT_NE(html.find("Not computed", map), std::string::npos);
  EXPECT_NE(html.find("Model 12: no accuracy map (the result has no parameter_covariance"),
            std::string::npos);
  EXPECT_EQ(Count(html, "<svg"), 4);
}

TEST(Report, WithoutTruthOrRulerRunsSaysWhatIsMissing) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  ValidationInputs in = PaperValidationInputs();
  in.truth.reset();
  in.straightness.clear();
  const ValidationReport report = Validate(in);
  EXPECT_FALSE(report.paper_scenario);
  const std::string html = FormatHtmlReport(in, report, "test");
  EXPECT_EQ(Count(html, "<svg"), 3);
  EXPECT_EQ(Count(html, "Not computed"), 4);
  EXPECT_EQ(html.find("(paper)"), std::string::npos);
}

TEST(Report, MeasuredSquareRunsAddTheirRowsAndFigure) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const ValidationInputs plain = PaperValidationInputs();
  const std::string without = FormatHtmlReport(plain, Validate(plain), "test");
  EXPECT_EQ(without.find(std::string("<section id=\"") + kMeasuredSquareSection),
            std::string::npos);

  ValidationInputs in = WithMeasuredSquares(PaperValidationInputs());
  in.square_measured[0].label = "a <priori>";  // escaped in the tables
  const ValidationReport report = Validate(in);
  const std::string html = FormatHtmlReport(in, report, "test");
  for (const char* id : kReportSections) {
    EXPECT_NE(html.find(std::string("<section id=\"") + id + "\">"), std::string::npos) << id;
  }
  EXPECT_NE(html.find(std::string("<section id=\"") + kMeasuredSquareSection + "\">"),
            std::string::npos);
  // Residuals, histograms, straightness, square, measured square.
  EXPECT_EQ(Count(html, "<svg"), 6);
  EXPECT_EQ(Count(html, "Not computed"), 0);
  EXPECT_NE(html.find("<th>a &lt;priori&gt; (measured)</th>"), std::string::npos);
  EXPECT_NE(html.find("<th>Model 12 (measured)</th>"), std::string::npos);
  EXPECT_EQ(html.find("<priori>"), std::string::npos);
  EXPECT_EQ(html.find("nan"), std::string::npos);
}

TEST(Report, MeasuredSquareRunsWithoutTruthStillFillTheSquareSection) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  ValidationInputs in = WithMeasuredSquares(PaperValidationInputs());
  in.truth.reset();
  const std::string html = FormatHtmlReport(in, Validate(in), "test");
  const size_t square = html.find("<section id=\"square\">");
  ASSERT_NE(square, std::string::npos);
  const size_t end = html.find("</section>", square);
  EXPECT_NE(html.substr(square, end - square).find("Model 12 (measured)"), std::string::npos);
  EXPECT_EQ(html.substr(square, end - square).find("Not computed"), std::string::npos);
  EXPECT_NE(html.find(std::string("<section id=\"") + kMeasuredSquareSection + "\">"),
            std::string::npos);
}

}  // namespace
}  // namespace h4::host
