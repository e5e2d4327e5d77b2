// The report's verdict section (host/report/report_verdict.h): the first section of the
// page, with each result's verdict and the figures that decided it, the rejected poses
// with score and reason, and the provenance; escaped; said plainly when a result has none.
#include "host/report/report_verdict.h"

#include <string>

#include <gtest/gtest.h>

#include "host/report/gnuplot_svg.h"
#include "host/report/html_report.h"
#include "tests/validation/validation_test_helpers.h"

namespace h4::host {
namespace {

ValidationInputs WithVerdicts() {
  ValidationInputs in = PaperValidationInputs();
  in.result12->verdict =
      ResultVerdict{"model_cannot_describe", "Use Model 31 <now>.", {{"reduced_chi2", 212.5}}};
  in.result12->rejected_details = {{17, 912.4, "held-out chi-square 912"}};
  in.result12->provenance = ResultProvenance{"0.1.0", "2026-11-23T20:01:02Z", {"data.csv"}};
  in.result12->cross_validation = CrossValidationFigures{10, 71, 3.1e-3, 1e-3, 250.0};
  return in;
}

TEST(ReportVerdict, ListsVerdictFiguresRejectedPosesAndProvenanceEscaped) {
  const std::string html = VerdictSection(WithVerdicts());
  EXPECT_NE(html.find("model_cannot_describe"), std::string::npos);
  EXPECT_NE(html.find("Use Model 31 &lt;now&gt;."), std::string::npos);
  EXPECT_NE(html.find("title=\"reduced_chi2\""), std::string::npos);
  EXPECT_NE(html.find("<tr><th>17</th><td>912</td><td>held-out chi-square 912</td></tr>"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("h4cal 0.1.0 on 2026-11-23T20:01:02Z"), std::string::npos);
  EXPECT_NE(html.find("10-fold cross-validation"), std::string::npos);
}

// The figures in words and in mm, deg or %, not the result's SI keys (kept on hover).
TEST(ReportVerdict, FiguresReadInWordsAndMillimetresNotJsonKeys) {
  ValidationInputs in = WithVerdicts();
  in.result12->verdict->figures = {{"position_misfit_m", 1.48e-5},
                                   {"chi2_upper_tail_probability", 1.135e-171},
                                   {"largest_angle_change_rad", 0.0123},
                                   {"a_future_figure", 2.5}};
  const std::string html = VerdictSection(in);
  EXPECT_NE(html.find("board position misfit, RMS over the poses in the fit (mm)</th><td>0.0148<"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("from the camera's noise alone</th><td>below 1e-6<"), std::string::npos);
  EXPECT_NE(html.find("(deg)</th><td>0.705<"), std::string::npos) << html;
  EXPECT_EQ(html.find(">position_misfit_m<"), std::string::npos) << html;
  EXPECT_EQ(html.find("1.135e-171"), std::string::npos);
  EXPECT_NE(html.find(">a_future_figure</th><td>2.5<"), std::string::npos);  // unknown: as is
  // In reading order, not the file's alphabetical one; unknown figures last.
  EXPECT_LT(html.find("probability of so large"), html.find("board position misfit"));
  EXPECT_LT(html.find("board position misfit"), html.find("largest angle change"));
  EXPECT_LT(html.find("largest angle change"), html.find("a_future_figure"));
}

TEST(ReportVerdict, AResultWithoutAVerdictSaysSo) {
  ValidationInputs in = WithVerdicts();
  in.result12->verdict.reset();
  in.result12->provenance.reset();
  const std::string html = VerdictSection(in);
  EXPECT_NE(html.find("No verdict recorded"), std::string::npos) << html;
  EXPECT_NE(html.find("does not record which h4cal made it"), std::string::npos) << html;
}

TEST(ReportVerdict, IsTheFirstSectionOfThePage) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const ValidationInputs in = WithVerdicts();
  const std::string html = FormatHtmlReport(in, Validate(in), "test");
  const size_t verdict = html.find("<section id=\"verdict\">");
  ASSERT_NE(verdict, std::string::npos);
  EXPECT_EQ(html.find("<section"), verdict);
  EXPECT_LT(verdict, html.find("<section id=\"summary\">"));
}

}  // namespace
}  // namespace h4::host
