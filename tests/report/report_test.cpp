// Tests of the HTML report (host/report): every section and figure is present, the page is
// self-contained (no script, nothing fetched), the paper's numbers stand beside ours on the
// paper scenario, text is escaped, and measured square runs bring their rows and figure.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <spdlog/fmt/fmt.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/identification/camera_parameters.h"
#include "host/kinematics/pose_plan.h"
#include "host/report/gnuplot_svg.h"
#include "host/report/html_report.h"
#include "host/report/html_table.h"
#include "host/report/pose_residuals.h"
#include "host/report/report_camera.h"
#include "host/report/report_tables.h"
#include "host/simulation/corner_campaign.h"
#include "tests/validation/validation_test_helpers.h"

namespace h4::host {
namespace {

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The page's text of section `id` (empty when absent).
std::string SectionText(const std::string& html, const std::string& id) {
  const size_t start = html.find("<section id=\"" + id + "\">");
  if (start == std::string::npos) return "";
  return html.substr(start, html.find("</section>", start) - start);
}

// "Not computed" outside the camera section, which says it once when the report knows
// nothing of the camera (no corner path, no corners).
int NotComputedOutsideCamera(const std::string& html) {
  const std::string camera = SectionText(html, "camera");
  EXPECT_EQ(Count(camera, "Not computed"), 1) << camera;
  return Count(html, "Not computed") - Count(camera, "Not computed");
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
  EXPECT_EQ(NotComputedOutsideCamera(html), 0);
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

// Issue 26 point 7: a per-pose residual table and residuals.csv (a Kalibr user looks for the
// poses a model misfits); one CSV row per dataset pose, four columns per model.
TEST(Report, ListsThePosesEachModelMisfitsMostAndWritesEveryResidual) {
  const ValidationInputs in = PaperValidationInputs();
  const ValidationReport report = Validate(in);
  const std::string csv = PoseResidualsCsv(report);
  ASSERT_EQ(report.models.size(), 2u);  // a priori and Model 12 on the paper scenario
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "pose_id,evaluated,apriori_q1_deg,apriori_q2_deg,apriori_q3_deg,apriori_q4_deg,"
            "model12_q1_deg,model12_q2_deg,model12_q3_deg,model12_q4_deg");
  EXPECT_EQ(Count(csv, "\n"), static_cast<int>(in.rows.size()) + 1);
  EXPECT_EQ(Count(csv, ",1,"), static_cast<int>(report.heldout_ids.size()));
  const std::string table = PoseResidualsTable(report);
  EXPECT_EQ(Count(table, "<tr><th>") - 1, 10) << table;  // a header, then the 10 worst poses
  EXPECT_NE(table.find("The 10 poses Model 12 misfits most"), std::string::npos) << table;
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const std::string dir = ::testing::TempDir() + "/report_residuals";
  WriteHtmlReport(dir, in, report, "test");
  std::ifstream written(dir + "/residuals.csv");
  const std::string text((std::istreambuf_iterator<char>(written)), {});
  EXPECT_EQ(text, csv);
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
  EXPECT_EQ(NotComputedOutsideCamera(html), 4);
  EXPECT_EQ(html.find("(paper)"), std::string::npos);
  // Sections that do not apply say so in neutral words, not as an error (red notes).
  EXPECT_EQ(Count(html, "<p class=\"not-applicable\">Not computed: "), 5);
  EXPECT_EQ(Count(html, "<p class=\"note\">Not computed"), 0);
  EXPECT_NE(html.find("optional: no ruler run given"), std::string::npos);
}

// Issue 43 point 8: a figure that rounds to zero reads 0, not -0, in the report's tables.
TEST(Report, TableCellsShowNoNegativeZero) {
  EXPECT_EQ(WithoutNegativeZeros("-0.0000"), "0.0000");
  EXPECT_EQ(WithoutNegativeZeros("-0"), "0");
  EXPECT_EQ(WithoutNegativeZeros("-0.0000, -0.0012, -0.0000"), "0.0000, -0.0012, 0.0000");
  EXPECT_EQ(WithoutNegativeZeros("-0.05"), "-0.05");
  EXPECT_EQ(WithoutNegativeZeros("-10.0"), "-10.0");
  EXPECT_EQ(WithoutNegativeZeros("1.2e-05"), "1.2e-05");
  EXPECT_EQ(WithoutNegativeZeros("(1, -0)"), "(1, 0)");
  EXPECT_EQ(WithoutNegativeZeros("run-0.csv, sq-0"), "run-0.csv, sq-0");
  EXPECT_EQ(Row("offset", {"-0.0000, 0.0100, -0.0000"}),
            "<tr><th>offset</th><td>0.0000, 0.0100, 0.0000</td></tr>\n");
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
  EXPECT_EQ(NotComputedOutsideCamera(html), 0);
  // Each run with its shape first and the frame it is judged in: Model 12's own for the
  // run it drove, Model 12's (not its own) for the a priori controller.
  EXPECT_NE(html.find("<th>a &lt;priori&gt;</th><td>"), std::string::npos);
  EXPECT_NE(html.find("</td><td>Model 12</td>"), std::string::npos);
  EXPECT_NE(html.find("<th>Model 12</th><td>0.0000</td><td>Model 12 (its own)</td>"),
            std::string::npos);
  EXPECT_EQ(html.find("Model 12 inverse kinematics, and the camera measured"), std::string::npos);
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
  EXPECT_NE(html.substr(square, end - square).find("<th>Model 12</th><td>0.0000</td>"),
            std::string::npos);
  EXPECT_EQ(html.substr(square, end - square).find("Not computed"), std::string::npos);
  EXPECT_NE(html.find(std::string("<section id=\"") + kMeasuredSquareSection + "\">"),
            std::string::npos);
}

// Every pose in the fit (identify's default): no pose is held out, so the summary must not
// say so; its headline is the cross-validated RMS, and the figures on the dataset's poses
// are labelled in-sample.
TEST(Report, EveryPoseInTheFitLeadsWithTheCrossValidatedRmsAndSaysInSample) {
  const ValidationInputs in = EveryPoseInTheFit();
  const std::string summary = SummaryTable(in, Validate(in));
  EXPECT_EQ(summary.find("held out for validation"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("held-out poses"), std::string::npos) << summary;
  const size_t headline = summary.find(
      "<tr><th>Model 12 board pose error, 10-fold cross-validated (held-out) RMS over 81 poses "
      "(mm / deg)</th><td>1.8734 / 0.1203</td>");
  const size_t in_sample = summary.find(
      "<tr><th>Model 12 positioning error, in-sample (81 poses, none held out of the fit) "
      "(RMS, mm / deg)</th><td>0.0000 / 0.0000</td>");
  ASSERT_NE(headline, std::string::npos) << summary;
  ASSERT_NE(in_sample, std::string::npos) << summary;
  EXPECT_LT(headline, in_sample) << "the held-out figure first";
}

// A real held-out set says how many poses the fit did not see, in RMS with 4 decimals.
TEST(Report, HeldOutPosesAreLabelledNotInTheFit) {
  const ValidationInputs in = PaperValidationInputs();
  const std::string summary = SummaryTable(in, Validate(in));
  EXPECT_NE(summary.find("<tr><th>Model 12 positioning error, held out (10 poses not in the fit) "
                         "(RMS, mm / deg)</th><td>0.0000 / 0.0000</td>"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("<tr><th>a priori positioning error, every pose (RMS, mm / deg)</th>"),
            std::string::npos)
      << summary;
  EXPECT_EQ(summary.find("in-sample"), std::string::npos) << summary;
}

// No part of the page (titles, tables, plots, captions) calls in-sample poses held out.
TEST(Report, EveryPoseInTheFitIsInSampleOnTheWholePage) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const ValidationInputs in = EveryPoseInTheFit();
  std::string html = FormatHtmlReport(in, Validate(in), "test");
  std::transform(html.begin(), html.end(), html.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  EXPECT_EQ(Count(html, "held-out pose"), 0);
  EXPECT_EQ(Count(html, "held out for validation"), 0);
  // Summary, Table 3 (title, contents, text), positioning, residual plot (title, caption).
  EXPECT_GE(Count(html, "in-sample (81 poses, none held out of the fit)"), 7);
}

// With corners, a refined camera and the camera-exact covariance, the camera section has its
// four parts: the intrinsics table (file, refined, sigma), the residual map's figure and
// summary (corners with 1e-6 px noise through the true robot and camera: nothing left), the
// board's coverage of the image, and the camera's share of the accuracy map (here half the
// variance: share = exact).
TEST(Report, TheCameraSectionShowsIntrinsicsResidualsAndTheCamerasShare) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const SimulatedRobot truth = PaperTruth();
  const BoardModel board(
      ReadBoardYaml(std::string(H4_SOURCE_DIR) + "/boards/aprilgrid_6x6_30mm.yaml"));
  const CameraIntrinsics camera =
      ReadCameraYaml(std::string(H4_SOURCE_DIR) + "/boards/sim_camera_1024x768.yaml");
  const CornerCampaign campaign =
      SimulateCornerCampaign(truth, GridPosePlan(), board, camera, camera,
                             {.sigma_px = 1e-6, .sigma_q = 0.0, .seed = 3, .valid_count = 10});
  ValidationInputs in = PaperValidationInputs();
  in.rows = campaign.rows;
  std::vector<int64_t> valid;
  for (const DatasetRow& row : campaign.rows) {
    if (row.set == PoseSet::kValid) valid.push_back(row.pose_id);
  }
  in.result12 = PerfectModel12Result(truth, valid);
  in.result12->parameter_covariance_camera_exact = 0.5 * *in.result12->parameter_covariance;
  ResultCamera refined;
  refined.distortion_model = ToString(camera.distortion_model);
  refined.width = camera.width;
  refined.height = camera.height;
  const std::vector<std::string> names = CameraParameterNames(camera);
  const Eigen::VectorXd values = CameraParameterValues(camera);
  for (size_t k = 0; k < names.size(); ++k) {
    const double v = values[static_cast<Eigen::Index>(k)];
    refined.parameters.push_back({names[k], v, k == 0 ? v + 0.8 : v,
                                  k < 4 ? std::optional<double>(0.2) : std::nullopt,
                                  k < 4 ? "" : "the corners cannot tell it"});
  }
  in.result12->camera = refined;
  in.corners = campaign.corners;
  in.board = board;
  in.camera = camera;

  const ValidationReport report = Validate(in);
  ASSERT_TRUE(report.corner_residuals.has_value());
  EXPECT_TRUE(report.corner_residuals->refined_camera);
  EXPECT_EQ(report.corner_residuals->corners, static_cast<int>(campaign.corners.size()));
  EXPECT_LT(report.corner_residuals->rms_px, 1e-4);
  ASSERT_TRUE(report.models.back().accuracy_map_camera_exact.has_value());
  const std::string html = FormatHtmlReport(in, report, "test");
  const std::string section = SectionText(html, "camera");
  EXPECT_EQ(Count(section, "Not computed"), 0) << section;
  // The corner residual map and the board's coverage of the image.
  EXPECT_EQ(Count(section, "<svg"), 2);
  EXPECT_NE(section.find("<h3>The board's coverage of the image</h3>\n<figure>"),
            std::string::npos);
  EXPECT_NE(section.find("<th>camera.fx</th><td>817.800</td><td>817.000</td>"), std::string::npos)
      << section;
  EXPECT_NE(section.find("<td>-0.800</td><td>0.200</td><td>-4.0</td>"), std::string::npos);
  EXPECT_NE(section.find("kept: the corners cannot tell it"), std::string::npos);
  const AccuracyMap& full = *report.models.back().accuracy_map;
  const double median_mm = 1e3 * full.MedianPositionSigma();
  EXPECT_NE(section.find(fmt::format("<td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td>", median_mm,
                                     1e3 * full.MaxPositionSigma(), median_mm / std::sqrt(2.0))),
            std::string::npos)
      << section;
  EXPECT_EQ(html.find("nan"), std::string::npos);

  // A pose the camera-exact map left out (its sigma not finite) costs only its own share,
  // not the poses after it: the largest share is still the full map's over sqrt(2).
  ValidationReport gap = report;
  AccuracyMap& exact = *gap.models.back().accuracy_map_camera_exact;
  exact.points.erase(exact.points.begin());
  double largest_mm = 0;
  for (size_t k = 1; k < full.points.size(); ++k) {
    largest_mm = std::max(largest_mm, 1e3 * full.points[k].position_sigma_m);
  }
  const std::string share_table = CameraShareTable(gap);
  EXPECT_NE(share_table.find(fmt::format("<td>{:.4f}</td></tr>", largest_mm / std::sqrt(2.0))),
            std::string::npos)
      << share_table;

  // The camera file's model must be the result's.
  in.camera->distortion_model = DistortionModel::kEquidistant;
  in.camera->distortion = Eigen::VectorXd::Zero(4);
  EXPECT_TRUE(ValidateRefuses(in, "is not the camera file's"));
}

}  // namespace
}  // namespace h4::host
