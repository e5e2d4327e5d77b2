// HTML tables of the report (see report_tables.h). The paper's own tables (2, 3, 4) keep its
// units (m, rad) so that its numbers compare by eye; every other figure is in mm and deg.
#include "host/report/report_tables.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include <spdlog/fmt/fmt.h>

#include "common/text/markup_escape.h"
#include "common/units.h"
#include "host/kinematics/model_parameters.h"
#include "host/kinematics/paper_robot.h"
#include "host/report/html_table.h"
#include "host/report/paper_numbers.h"

namespace h4::host {
namespace {

std::string Sci(double v) { return fmt::format("{:.1e}", v); }
// 4 decimals: Model 31 results differ from each other by hundredths of a millimetre.
std::string Mm(double v) { return fmt::format("{:.4f}", v * 1e3); }
std::string Deg(double rad, int decimals) {
  return fmt::format("{:.{}f}", DegreesFromRadians(rad), decimals);
}
std::string MmDeg(double m, double rad) { return Mm(m) + " / " + Deg(rad, 4); }

std::vector<std::string> Sci4(const std::array<double, 4>& v) {
  return {Sci(v[0]), Sci(v[1]), Sci(v[2]), Sci(v[3])};
}

// A parameter's value as people read it: deg for angles, mm for lengths.
std::string ParameterValue(const std::string& name, double value_si) {
  return IsAngleParameter(name) ? fmt::format("{:.5g}", DegreesFromRadians(value_si))
                                : fmt::format("{:.6g}", value_si * 1e3);
}

std::array<double, 12> Table2Row(const Model12Parameters& p) {
  return {p.h,        p.arm,      p.R,     p.forearm, p.alpha[0], p.alpha[1],
          p.alpha[2], p.alpha[3], p.q0[0], p.q0[1],   p.q0[2],    p.q0[3]};
}

// Which poses the figures below the table are on, and where the held-out accuracy is.
std::string SummaryPoses(const ValidationInputs& in, const ValidationReport& report) {
  const std::string dataset = MarkupEscape(in.dataset_name);
  if (!report.in_sample) {
    return fmt::format("<p>{} poses in {}, {} held out for validation (not in the fit).</p>\n",
                       in.rows.size(), dataset, report.heldout_ids.size());
  }
  bool cross_validated = false;
  for (const auto& v : report.models) cross_validated = cross_validated || v.cross_validation;
  return fmt::format(
      "<p>{} poses in {}, none held out of the fit: the figures on them are in-sample.{}</p>\n",
      in.rows.size(), dataset,
      cross_validated ? " The held-out accuracy is the k-fold cross-validated "
                        "one (each pose predicted by the model fitted without "
                        "its fold)."
                      : "");
}

}  // namespace

// The headline first: each model's held-out accuracy (cross-validated), then the figures
// on the evaluated poses, labelled held out or in-sample. RMS throughout; the a priori mean
// only beside the paper's, which is a mean.
std::string SummaryTable(const ValidationInputs& in, const ValidationReport& report) {
  const bool paper = report.paper_scenario;
  std::string t;
  t += "<table>\n" + Header(paper ? std::vector<std::string>{"figure", "ours", "paper"}
                                  : std::vector<std::string>{"figure", "ours"});
  auto add = [&](const std::string& what, const std::string& ours, const std::string& theirs) {
    std::vector<std::string> cells{ours};
    if (paper) cells.push_back(theirs);
    t += Row(what, cells);
  };
  for (const auto& v : report.models) {
    if (!v.cross_validation) continue;
    add(v.label + " board pose error, " + CrossValidatedLabel(*v.cross_validation) + " (mm / deg)",
        MmDeg(v.cross_validation->position_rms_m, v.cross_validation->rotation_rms_rad), "-");
  }
  add("a priori positioning error, every pose (RMS, mm / deg)",
      MmDeg(report.apriori_all.position_rms, report.apriori_all.theta_rms), "-");
  if (paper) {
    add("a priori positioning error, every pose (mean, as the paper gives it; mm / deg)",
        MmDeg(report.apriori_all.position_mean, report.apriori_all.theta_mean),
        MmDeg(paper::kAprioriPosition, paper::kAprioriTheta));
  }
  for (size_t m = 1; m < report.models.size(); ++m) {
    const auto& v = report.models[m];
    add(v.label + " positioning error, " + EvaluatedPosesLabel(report) + " (RMS, mm / deg)",
        MmDeg(v.positioning.position_rms, v.positioning.theta_rms), "-");
  }
  for (size_t m = 0; m < report.models.size(); ++m) {
    if (!report.models[m].square) continue;
    add("square path, " + report.models[m].label + " controller (side RMS, mm)",
        Mm(report.models[m].square->rms), m == 0 ? "about 5" : "under 0.5");
  }
  for (const auto& m : report.measured_squares) {
    add("square path measured by the camera, " + MarkupEscape(m.label) +
            " controller (shape RMS, offset removed, mm)",
        Mm(m.run.shape_rms), "-");
  }
  add("4-DoF check: rotation axis spread (deg)",
      report.prior.ok ? fmt::format("{:.3f}", report.prior.axis_spread_deg) : "not computed",
      fmt::format("{:.2f}", paper::kAxisSpreadDeg));
  t += "</table>\n" + SummaryPoses(in, report);
  return t;
}

std::string ParameterTables(const ValidationInputs& in) {
  std::string t;
  for (const auto* result : {&in.result12, &in.result31}) {
    if (!*result) continue;
    const IdentificationResult& r = **result;
    t += "<h3>" + ModelLabel(r.model) +
         "</h3>\n"
         "<table>\n" +
         Header({"parameter", "unit", "a priori", "identified", "one sigma", "status",
                 "reason fixed"});
    for (const ResultParameter& p : r.parameters) {
      std::string reason;
      for (const FixedParameter& f : r.fixed) {
        if (f.name == p.name) reason = f.reason;
      }
      const double std_scale = IsAngleParameter(p.name) ? DegreesFromRadians(1.0) : 1e3;
      t += Row(
          MarkupEscape(p.name),
          {IsAngleParameter(p.name) ? "deg" : "mm", ParameterValue(p.name, p.apriori),
           ParameterValue(p.name, p.value), p.std ? fmt::format("{:.2g}", *p.std * std_scale) : "-",
           p.fixed ? "fixed" : "identified", MarkupEscape(reason)},
          p.fixed ? "fixed" : "");
    }
    t += "</table>\n";
  }
  return t;
}

std::string IdentifiabilityTable(const ValidationInputs& in) {
  std::string t;
  t += "<table>\n" + Header({"model", "estimator", "condition number (scaled)", "fixed parameters",
                             "strong correlations (|rho| &gt; 0.9)"});
  for (const auto* result : {&in.result12, &in.result31}) {
    if (!*result) continue;
    const IdentificationResult& r = **result;
    std::string fixed, correlations;
    for (const auto& f : r.fixed) fixed += MarkupEscape(f.name) + "<br>";
    for (const auto& c : r.correlations) {
      correlations +=
          fmt::format("{} / {}: {:.3f}<br>", MarkupEscape(c.a), MarkupEscape(c.b), c.correlation);
    }
    t += Row(ModelLabel(r.model),
             {MarkupEscape(r.estimator.empty() ? "-" : r.estimator),
              r.condition_number ? fmt::format("{:.3g}", *r.condition_number) : "-",
              fixed.empty() ? "none" : fixed, correlations.empty() ? "none" : correlations});
  }
  t += "</table>\n";
  return t;
}

std::string Table2(const ValidationInputs& in, const ValidationReport& report) {
  std::string t;
  t += "<table>\n" + Header({"", "h (m)", "l (m)", "R (m)", "L (m)", "alpha1", "alpha2", "alpha3",
                             "alpha4", "q01", "q02", "q03", "q04"});
  auto add = [&](const std::string& label, const Model12Parameters& p, const std::string& css) {
    std::vector<std::string> cells;
    for (double v : Table2Row(p)) cells.push_back(fmt::format("{:.4f}", v));
    t += Row(label, cells, css);
  };
  add("a priori", in.apriori.model12, "");
  if (in.result12) {
    Model12Parameters p = in.apriori.model12;
    auto value = [&](const std::string& name, double fallback) {
      const ResultParameter* found = in.result12->Find(name);
      return found ? found->value : fallback;
    };
    p.h = value("h", p.h);
    p.arm = value("arm", p.arm);
    p.R = value("R", p.R);
    p.forearm = value("forearm", p.forearm);
    for (int i = 0; i < 4; ++i) {
      p.alpha[i] = value(fmt::format("alpha{}", i + 1), p.alpha[i]);
      p.q0[i] = value(fmt::format("q0{}", i + 1), p.q0[i]);
    }
    add("identified (Model 12, ours)", p, "ours");
  }
  if (report.paper_scenario) add("identified (paper)", kPaperIdentifiedModel12, "paper");
  if (in.truth && !in.truth->robot.model31 && !report.paper_scenario) {
    add("true (simulation)", in.truth->robot.model12, "");
  }
  t += "</table>\n";
  if (report.paper_scenario) {
    t += "<p>Paper scenario: the simulated true robot is the paper's identified row, so ours "
         "should match it within the measurement noise.</p>\n";
  }
  return t;
}

std::string Table3(const ValidationReport& report) {
  std::string t;
  t += "<table>\n" + Header({"", "", "q1", "q2", "q3", "q4"});
  auto add = [&](const std::string& label, const std::array<double, 4>& mean,
                 const std::array<double, 4>& rms, const std::string& css) {
    std::vector<std::string> m = Sci4(mean), r = Sci4(rms);
    m.insert(m.begin(), "mean");
    r.insert(r.begin(), "RMS");
    t += Row(label, m, css) + Row("", r, css);
  };
  const bool paper = report.paper_scenario;
  for (const auto& v : report.models) {
    const std::string label = v.label == "a priori" ? "before calibration" : "after " + v.label;
    add(label + (paper ? " (ours)" : ""), v.heldout.mean, v.heldout.rms, "ours");
    if (!paper) continue;
    if (v.label == "a priori") {
      add(label + " (paper)", paper::kTable3MeanBefore, paper::kTable3RmsBefore, "paper");
    } else if (v.label == "Model 12") {
      add(label + " (paper)", paper::kTable3Mean12, paper::kTable3Rms12, "paper");
    } else if (v.label == "Model 31") {
      add(label + " (paper)", paper::kTable3Mean31, paper::kTable3Rms31, "paper");
    }
  }
  t += "</table>\n";
  t += fmt::format(
      "<p>Residuals q~ - IK(X_BC X_CT X_TE) in rad, wrapped, {} (measured minus model, the "
      "paper's sign); mean and RMS as in the paper's table. Before calibration: the a priori "
      "Model 12 with the identified camera and board placement.</p>\n",
      EvaluatedPosesLabel(report));
  return t;
}

std::string PositioningTable(const ValidationReport& report) {
  std::string t;
  t += "<table>\n" + Header({"model", "poses", "position RMS (mm)", "theta RMS (deg)",
                             "position mean (mm)", "theta mean (deg)", "FK failures"});
  auto add = [&](const std::string& label, const PositioningError& e) {
    t +=
        Row(label, {fmt::format("{}", e.poses), Mm(e.position_rms), Deg(e.theta_rms, 4),
                    Mm(e.position_mean), Deg(e.theta_mean, 4), fmt::format("{}", e.failed.size())});
  };
  add("a priori, every pose", report.apriori_all);
  for (const auto& v : report.models)
    add(v.label + ", " + EvaluatedPosesLabel(report), v.positioning);
  t += "</table>\n<p>Forward kinematics of the encoder readings against the measured "
       "end-effector pose X_BC X_CT X_TE.</p>\n";
  if (report.paper_scenario) {
    t += "<p>Paper: a priori positioning error 26 mm and 0.022 rad (1.26 deg), mean.</p>\n";
  }
  return t;
}

namespace {

// Median and largest position sigma of the map's points at one Z level and theta.
std::pair<double, double> SliceSigmas(const AccuracyMap& map, double z, double theta) {
  std::vector<double> sigmas;
  for (const AccuracyMapPoint& point : map.points) {
    if (point.x[2] == z && point.x[3] == theta) sigmas.push_back(point.position_sigma_m);
  }
  if (sigmas.empty()) return {0.0, 0.0};
  std::sort(sigmas.begin(), sigmas.end());
  return {sigmas[sigmas.size() / 2], sigmas.back()};
}

}  // namespace

std::string AccuracyMapTable(const ValidationReport& report) {
  std::string t;
  for (const ModelValidation& v : report.models) {
    if (!v.accuracy_map) continue;
    const AccuracyMap& map = *v.accuracy_map;
    t += "<table>\n" + Header({v.label + ": Z from the centre (mm)", "theta (deg)",
                               "median 1-sigma position error (mm)", "largest (mm)"});
    for (double dz : map.options.z_offsets_m) {
      for (double theta : map.options.theta_rad) {
        const auto [median, largest] = SliceSigmas(map, map.centre[2] + dz, theta);
        t += Row(fmt::format("{:+.0f}", dz * 1e3),
                 {Deg(theta, 0), fmt::format("{:.4f}", median * 1e3),
                  fmt::format("{:.4f}", largest * 1e3)});
      }
    }
    t += fmt::format(
        "</table>\n<p>{}: {} poses, median {:.4f} mm, largest {:.4f} mm; {} grid poses out of "
        "reach or singular left out.</p>\n",
        v.label, map.points.size(), map.MedianPositionSigma() * 1e3, map.MaxPositionSigma() * 1e3,
        map.left_out);
  }
  return t;
}

std::string Table4(const ValidationReport& report) {
  std::string t;
  const size_t runs = report.models.front().straightness.size();
  std::vector<std::string> head{""};
  for (size_t r = 0; r < runs; ++r) {
    head.push_back(fmt::format("direction {} (m)", r + 1));
    head.push_back("improvement");
  }
  t += "<table>\n" + Header(head);
  const bool paper = report.paper_scenario && runs == 2;
  for (size_t m = 0; m < report.models.size(); ++m) {
    const auto& v = report.models[m];
    std::vector<std::string> cells;
    for (size_t r = 0; r < runs; ++r) {
      cells.push_back(Sci(v.straightness[r].fit.rms_distance));
      cells.push_back(
          m == 0 ? "-" : fmt::format("{:.0f} %", report.StraightnessImprovementPercent(m, r)));
    }
    const std::string label = m == 0 ? "before calibration" : "after " + v.label;
    t += Row(label + (paper ? " (ours)" : ""), cells, "ours");
    if (!paper) continue;
    const std::array<double, 2>* theirs = m == 0                  ? &paper::kTable4Before
                                          : v.label == "Model 12" ? &paper::kTable4Model12
                                          : v.label == "Model 31" ? &paper::kTable4Model31
                                                                  : nullptr;
    if (!theirs) continue;
    std::vector<std::string> paper_cells;
    for (size_t r = 0; r < 2; ++r) {
      paper_cells.push_back(Sci((*theirs)[r]));
      paper_cells.push_back(
          m == 0 ? "-"
                 : fmt::format("{:.0f} %", 100.0 * (paper::kTable4Before[r] - (*theirs)[r]) /
                                               paper::kTable4Before[r]));
    }
    t += Row(label + " (paper)", paper_cells, "paper");
  }
  t += "</table>\n<p>RMS distance of the forward-kinematics positions to their least-squares "
       "line, the end-effector sliding along a straight ruler.</p>\n";
  return t;
}

namespace {

// The squares the camera measured: the shape first (no frame needed), then the side errors
// and the offset in the base frame of the model that drove each run.
std::string MeasuredSquareTable(const ValidationInputs& in, const ValidationReport& report) {
  const SquareOptions& sq = in.square_plan->options;
  std::string t = fmt::format(
      "<p>Measured by the camera: the robot was driven through the {} points of a {:.1f} mm "
      "square centred at ({:.1f}, {:.1f}, {:.1f}) mm in B by each controller's own inverse "
      "kinematics, and the camera measured the board at each point. A measured position is "
      "that of X_BE = X_BC X_CT X_TE, with the camera and board placement (X_BC, X_TE) of the "
      "model named in the column \"judged in\": the one that drove the run, so that B is its "
      "own base frame. The shape (offset removed) needs no frame. The offset is the mean "
      "measured - commanded position: in the run's own frame, that model's absolute error; a "
      "run judged in another model's frame (the a priori controller has no camera placement of "
      "its own) also carries the difference between the two base frames.</p>\n",
      in.square_plan->pose_ids.size(), sq.side * 1e3, sq.centre[0] * 1e3, sq.centre[1] * 1e3,
      sq.centre[2] * 1e3);
  t += "<table>\n" + Header({"measured run", "shape RMS, offset removed (mm)", "judged in",
                             "side 1 RMS (mm)", "side 2", "side 3", "side 4", "max (mm)",
                             "mean |measured - commanded| (mm)", "offset X, Y, Z (mm)",
                             "points measured", "dataset", "missing pose ids"});
  for (const auto& m : report.measured_squares) {
    const SquareRun& s = m.run;
    double max = 0.0;
    for (const auto& side : s.sides) max = std::max(max, side.max);
    t += Row(MarkupEscape(m.label),
             {Mm(s.shape_rms), ModelLabel(m.frame) + (m.own_frame ? " (its own)" : ""),
              Mm(s.sides[0].rms), Mm(s.sides[1].rms), Mm(s.sides[2].rms), Mm(s.sides[3].rms),
              Mm(max), Mm(s.mean_position_error),
              fmt::format("{}, {}, {}", Mm(s.offset[0]), Mm(s.offset[1]), Mm(s.offset[2])),
              fmt::format("{} of {}", s.reached.size(), m.planned), MarkupEscape(m.dataset_name),
              m.missing_ids.empty() ? "none" : MarkupEscape(PoseIdList(m.missing_ids))},
             "measured");
  }
  return t + "</table>\n";
}

}  // namespace

std::string SquareTable(const ValidationInputs& in, const ValidationReport& report) {
  std::string t;
  bool simulated = false;
  for (const auto& v : report.models) simulated = simulated || v.square.has_value();
  if (simulated) {
    t += "<table>\n" +
         Header({"controller", "side 1 RMS (mm)", "side 2", "side 3", "side 4", "max (mm)",
                 "shape RMS, offset removed (mm)", "mean |reached - commanded| (mm)"});
    for (const auto& v : report.models) {
      if (!v.square) continue;
      const SquareRun& s = *v.square;
      double max = 0.0;
      for (const auto& side : s.sides) max = std::max(max, side.max);
      t += Row(v.label, {Mm(s.sides[0].rms), Mm(s.sides[1].rms), Mm(s.sides[2].rms),
                         Mm(s.sides[3].rms), Mm(max), Mm(s.shape_rms), Mm(s.mean_position_error)});
    }
    t += "</table>\n";
    t += fmt::format(
        "<p>A {:.0f} mm square centred at ({:.0f}, {:.0f}, {:.0f}) mm in B; the controller "
        "commands Model 12 inverse kinematics of each point, the true robot reaches the forward "
        "kinematics of those joints. Side error: distance of the reached points to the "
        "commanded side.{}</p>\n",
        in.square.side * 1e3, in.square.centre[0] * 1e3, in.square.centre[1] * 1e3,
        in.square.centre[2] * 1e3,
        report.paper_scenario ? " Paper: about 5 mm before calibration, under 0.5 mm after." : "");
  }
  if (!report.measured_squares.empty() && in.square_plan) t += MeasuredSquareTable(in, report);
  return t;
}

std::string FourDofTable(const ValidationReport& report) {
  std::string t;
  const PriorAnalysis& p = report.prior;
  t += "<table>\n" + Header({"check", "value"});
  t += Row("status", {p.ok ? "ok" : "not computed: " + MarkupEscape(p.message)});
  t += Row("poses used", {fmt::format("{}", p.poses_used)});
  t += Row("rotation axis spread in C (deg)", {fmt::format("{:.3f}", p.axis_spread_deg)});
  t += Row("rotation axis spread in T (deg)", {fmt::format("{:.3f}", p.axis_spread_T_deg)});
  t += Row("axis in C",
           {fmt::format("({:.4f}, {:.4f}, {:.4f})", p.axis_C[0], p.axis_C[1], p.axis_C[2])});
  t += Row("a priori camera axis correction (deg)",
           {fmt::format("{:.3f}", p.camera_axis_correction_deg)});
  t += Row("a priori board axis correction (deg)",
           {fmt::format("{:.3f}", p.board_axis_correction_deg)});
  if (report.paper_scenario) t += Row("paper: axis spread (deg)", {"0.12"});
  t += "</table>\n<p>All measured board rotations should turn about one axis if the robot "
       "has 4 degrees of freedom (paper III.B).</p>\n";
  return t;
}

}  // namespace h4::host
