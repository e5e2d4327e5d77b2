// Tests of the report's figures (host/report/report_figures.h), read from their gnuplot
// scripts (issue 26 point 7, "a report a technician reads at a glance"): every range follows
// its data, no legend sits on the data, the held-out axis is the dataset's pose ids, the
// accuracy map is drawn per model with the calibration poses, and the board's coverage of
// the image is drawn when the camera is known.
#include "host/report/report_figures.h"

#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/units.h"
#include "host/kinematics/pose_plan.h"
#include "host/report/gnuplot_svg.h"
#include "host/report/html_report.h"
#include "host/simulation/corner_campaign.h"
#include "tests/validation/validation_test_helpers.h"

namespace h4::host {
namespace {

// The rows of gnuplot data block `name` ($name << EOD ... EOD), each split into numbers.
std::vector<std::vector<double>> DataBlock(const std::string& script, const std::string& name) {
  std::vector<std::vector<double>> rows;
  const size_t start = script.find("$" + name + " << EOD\n");
  if (start == std::string::npos) return rows;
  std::istringstream lines(script.substr(script.find('\n', start) + 1));
  for (std::string line; std::getline(lines, line) && line != "EOD";) {
    std::istringstream fields(line);
    std::vector<double> row;
    for (std::string v; fields >> v;) row.push_back(std::stod(v));  // stod reads NaN
    rows.push_back(row);
  }
  return rows;
}

// The script's commands outside its data blocks.
std::vector<std::string> Commands(const std::string& script) {
  std::vector<std::string> commands;
  std::istringstream lines(script);
  bool in_block = false;
  for (std::string line; std::getline(lines, line);) {
    if (in_block) {
      in_block = line != "EOD";
    } else if (line.find("<< EOD") != std::string::npos) {
      in_block = true;
    } else {
      commands.push_back(line);
    }
  }
  return commands;
}

// A report of three models whose residuals differ by orders of magnitude, as a real
// campaign's do: a priori ~0.5 deg, Model 12 ~0.05 deg, Model 31 ~0.001 deg; the evaluated
// poses have ids that are not their index.
ValidationReport ReportOfThreeModels() {
  ValidationReport report;
  report.heldout_ids = {101, 205, 307, 412};
  const double scales_deg[] = {0.5, 0.05, 0.001};
  const char* labels[] = {"a priori", "Model 12", "Model 31"};
  for (int m = 0; m < 3; ++m) {
    ModelValidation v;
    v.label = labels[m];
    for (int k = 0; k < 80; ++k) {
      std::array<double, 4> r{};
      for (int j = 0; j < 4; ++j) {
        r[j] = RadiansFromDegrees(scales_deg[m] * std::sin(0.7 * k + 1.3 * j));
      }
      v.all.residuals.push_back(r);
      v.all.pose_ids.push_back(k + 1);
    }
    v.heldout.pose_ids = report.heldout_ids;
    v.heldout.residuals.assign(v.all.residuals.begin(), v.all.residuals.begin() + 4);
    v.heldout.poses = 4;
    report.models.push_back(v);
  }
  return report;
}

// Model 31's residuals of 0.001 deg fill bins across their own range, not one bar on the
// axis of Model 12's larger ones.
TEST(ReportFigures, EachHistogramSpansItsOwnModelsResiduals) {
  const GnuplotPlot plot = HistogramPlot(ReportOfThreeModels());
  const std::vector<std::vector<double>> bins = DataBlock(plot.script, "h2");
  ASSERT_FALSE(bins.empty()) << plot.script;
  int filled = 0;
  for (const auto& bin : bins) {
    EXPECT_LE(std::abs(bin[0]), 0.0015) << "a Model 31 bin centred outside its residuals";
    if (bin[1] > 0) ++filled;
  }
  EXPECT_GE(filled, 5) << plot.script;
  // Each panel's axis is set from its data: Model 31's within a few thousandths of a deg.
  const std::regex range(R"(set xrange \[([-0-9.e+]+):([-0-9.e+]+)\])");
  std::vector<std::pair<double, double>> ranges;
  for (const std::string& command : Commands(plot.script)) {
    std::smatch m;
    if (std::regex_search(command, m, range)) ranges.push_back({std::stod(m[1]), std::stod(m[2])});
  }
  ASSERT_EQ(ranges.size(), 3u) << plot.script;
  EXPECT_GT(ranges[2].first, -0.002);
  EXPECT_LT(ranges[2].second, 0.002);
  EXPECT_LT(ranges[2].first, -0.0009);
  EXPECT_GT(ranges[2].second, 0.0009);
  EXPECT_GT(ranges[0].second, 0.4) << "the a priori panel spans its own residuals";
}

// The held-out residuals are plotted against the dataset's pose ids, not 1..N.
TEST(ReportFigures, TheHeldOutAxisIsThePoseIds) {
  const ValidationReport report = ReportOfThreeModels();
  const GnuplotPlot plot = ResidualsPlot(report);
  for (const char* block : {"r0", "r1", "r2"}) {
    const std::vector<std::vector<double>> rows = DataBlock(plot.script, block);
    ASSERT_EQ(rows.size(), 4u) << plot.script;
    for (size_t k = 0; k < rows.size(); ++k) {
      EXPECT_EQ(rows[k][0], static_cast<double>(report.heldout_ids[k])) << block;
    }
  }
  EXPECT_NE(plot.script.find("set xlabel 'held-out pose id'"), std::string::npos) << plot.script;
}

// Every figure's legend is outside its plot area (or there is none): none covers data.
TEST(ReportFigures, NoLegendIsInsideAPlot) {
  ValidationInputs in = WithMeasuredSquares(PaperValidationInputs());
  const ValidationReport report = Validate(in);
  ASSERT_TRUE(report.models.back().accuracy_map.has_value());
  const std::vector<GnuplotPlot> plots = {
      ResidualsPlot(report),
      HistogramPlot(report),
      StraightnessPlot(report),
      SquarePlot(report),
      MeasuredSquarePlot(*in.square_plan, report),
      AccuracyMapPlot(*report.models.back().accuracy_map, "Model 12",
                      report.models.back().calibration_poses, report.models.back().evaluated_poses),
  };
  for (const GnuplotPlot& plot : plots) {
    int keys = 0;
    for (const std::string& command : Commands(plot.script)) {
      if (command.rfind("set key", 0) != 0) continue;
      ++keys;
      EXPECT_NE(command.find("outside"), std::string::npos) << command;
    }
    if (keys == 0) {
      EXPECT_NE(plot.script.find("unset key"), std::string::npos) << plot.script;
    }
  }
}

// The accuracy map marks where the calibration poses and the held-out ones lie, each series
// with its legend entry; on the paper grid, the 71 calibration and 10 held-out poses.
TEST(ReportFigures, TheAccuracyMapMarksTheCalibrationAndHeldOutPoses) {
  const ValidationInputs in = PaperValidationInputs();
  const ValidationReport report = Validate(in);
  const ModelValidation& model12 = report.models.back();
  ASSERT_TRUE(model12.accuracy_map.has_value());
  EXPECT_EQ(model12.calibration_poses.size(), 71u);
  EXPECT_EQ(model12.evaluated_poses.size(), 10u);
  const GnuplotPlot plot = AccuracyMapPlot(*model12.accuracy_map, model12.label,
                                           model12.calibration_poses, model12.evaluated_poses);
  EXPECT_NE(plot.script.find("title 'calibration pose'"), std::string::npos) << plot.script;
  EXPECT_NE(plot.script.find("title 'held-out pose'"), std::string::npos) << plot.script;
  size_t calibration = 0, held_out = 0;
  for (int t = 0; t < 3; ++t) {
    for (int l = 0; l < 3; ++l) {
      for (const auto& row : DataBlock(plot.script, fmt::format("c{}_{}", t, l))) {
        if (!std::isnan(row[0])) ++calibration;
      }
      for (const auto& row : DataBlock(plot.script, fmt::format("e{}_{}", t, l))) {
        if (!std::isnan(row[0])) ++held_out;
      }
    }
  }
  EXPECT_EQ(calibration, 71u);
  EXPECT_EQ(held_out, 10u);
}

// Model 12 and Model 31 identified: the accuracy map section has a figure for each.
TEST(ReportFigures, TheAccuracyMapIsDrawnForEveryIdentifiedModel) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const ValidationInputs in = PaperValidationInputs();
  ValidationReport report = Validate(in);
  ModelValidation model31 = report.models.back();  // a stand-in: the figure is per model
  model31.label = "Model 31";
  report.models.push_back(model31);
  const std::string html = FormatHtmlReport(in, report, "test");
  const size_t start = html.find("<section id=\"accuracy-map\">");
  const std::string section = html.substr(start, html.find("</section>", start) - start);
  int figures = 0;
  for (size_t at = section.find("<svg"); at != std::string::npos; at = section.find("<svg", at + 1))
    ++figures;
  EXPECT_EQ(figures, 2) << "one accuracy map per identified model";
  EXPECT_NE(section.find("<figcaption>Model 12"), std::string::npos);
  EXPECT_NE(section.find("<figcaption>Model 31"), std::string::npos);
}

// With the camera known, the board's outline in every dataset pose, projected into the
// image, over the image rectangle (v down).
TEST(ReportFigures, TheBoardsCoverageOfTheImageShowsEveryPose) {
  const BoardModel board(
      ReadBoardYaml(std::string(H4_SOURCE_DIR) + "/boards/aprilgrid_6x6_30mm.yaml"));
  const CameraIntrinsics camera =
      ReadCameraYaml(std::string(H4_SOURCE_DIR) + "/boards/sim_camera_1024x768.yaml");
  const CornerCampaign campaign =
      SimulateCornerCampaign(PaperTruth(), GridPosePlan(), board, camera, camera,
                             {.sigma_px = 1e-6, .sigma_q = 0.0, .seed = 3, .valid_count = 10});
  std::vector<int64_t> held_out;
  for (const DatasetRow& row : campaign.rows) {
    if (row.set == PoseSet::kValid) held_out.push_back(row.pose_id);
  }
  const GnuplotPlot plot = BoardCoveragePlot(campaign.rows, held_out, board, camera);
  EXPECT_NE(plot.script.find("set xrange [0:1024]"), std::string::npos) << plot.script;
  EXPECT_NE(plot.script.find("set yrange [768:0]"), std::string::npos) << plot.script;
  // One centre per pose, each inside the image.
  const auto calib_centres = DataBlock(plot.script, "calib_centres");
  const auto valid_centres = DataBlock(plot.script, "valid_centres");
  EXPECT_EQ(calib_centres.size() + valid_centres.size(), campaign.rows.size());
  EXPECT_EQ(valid_centres.size(), held_out.size());
  for (const auto& c : calib_centres) {
    EXPECT_GT(c[0], 0.0);
    EXPECT_LT(c[0], 1024.0);
    EXPECT_GT(c[1], 0.0);
    EXPECT_LT(c[1], 768.0);
  }
  EXPECT_NE(plot.script.find("title 'calibration pose (board outline)'"), std::string::npos);
  EXPECT_NE(plot.script.find("title 'held-out pose (board outline)'"), std::string::npos);
}

}  // namespace
}  // namespace h4::host
