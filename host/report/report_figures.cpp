// gnuplot scripts of the report's figures (see report_figures.h). Data go inline as
// gnuplot data blocks; values are converted to deg and mm for reading, as in the tables.
#include "host/report/report_figures.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <spdlog/fmt/fmt.h>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/units.h"
#include "host/report/gnuplot_svg.h"

namespace h4::host {
namespace {

constexpr const char* kColours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e"};

std::string Block(const std::string& name, const std::string& body) {
  return "$" + name + " << EOD\n" + body + "EOD\n";
}

std::string Quoted(const std::string& s) { return "'" + s + "'"; }

// Text for inside a gnuplot single-quoted string: a quote is written twice.
std::string GnuplotText(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out;
}

// Explicit ticks at the evaluated poses' ids when they are few enough to read; beyond, the
// axis's own ticks (still pose ids).
std::string PoseIdTics(const std::vector<int64_t>& ids) {
  if (ids.empty() || ids.size() > 30) return "";
  std::string tics;
  for (int64_t id : ids) tics += fmt::format("{}'{}' {}", tics.empty() ? "" : ", ", id, id);
  return "set xtics (" + tics + ") rotate by -90 font ',8'\n";
}

// Counts of values in equal bins across their own range [lo, lo + bins * width].
struct ResidualHistogram {
  double lo = 0.0;
  double width = 1.0;
  std::vector<int> counts;
  double hi() const { return lo + width * static_cast<double>(counts.size()); }
};

// About the square root of the count of bins (5 to 25), so that a spread shows as a shape;
// values all alike get a narrow range around them rather than a made-up one.
ResidualHistogram HistogramOf(const std::vector<double>& values) {
  ResidualHistogram h;
  if (values.empty()) {
    h.lo = -0.5;
    h.counts.assign(1, 0);
    return h;
  }
  const auto [min, max] = std::minmax_element(values.begin(), values.end());
  const int bins =
      std::clamp(static_cast<int>(std::sqrt(static_cast<double>(values.size()))), 5, 25);
  double lo = *min, hi = *max;
  if (hi - lo < 1e-12) {
    const double pad = std::max(1e-9, 1e-3 * std::abs(lo));
    lo -= pad;
    hi += pad;
  }
  h.lo = lo;
  h.width = (hi - lo) / bins;
  h.counts.assign(static_cast<size_t>(bins), 0);
  for (double v : values) {
    const int b = std::clamp(static_cast<int>(std::floor((v - lo) / h.width)), 0, bins - 1);
    ++h.counts[static_cast<size_t>(b)];
  }
  return h;
}

// The poses whose nearest Z level and theta are panel (t, l)'s, as X, Y from the map's
// centre (mm); NaN when none, so that the panel's series still exists.
std::string PosesInPanel(const AccuracyMap& map, const std::vector<EePose>& poses, size_t t,
                         size_t l) {
  const auto nearest = [](const std::vector<double>& values, double v) {
    size_t best = 0;
    for (size_t k = 1; k < values.size(); ++k) {
      if (std::abs(values[k] - v) < std::abs(values[best] - v)) best = k;
    }
    return best;
  };
  std::string body;
  for (const EePose& x : poses) {
    if (nearest(map.options.z_offsets_m, x[2] - map.centre[2]) != l ||
        nearest(map.options.theta_rad, x[3]) != t) {
      continue;
    }
    body +=
        fmt::format("{:.6g} {:.6g}\n", (x[0] - map.centre[0]) * 1e3, (x[1] - map.centre[1]) * 1e3);
  }
  return body.empty() ? "NaN NaN\n" : body;
}

// The board's outline in its own frame T: the rectangle around its corners (the printed
// board's edge lies a margin beyond), sampled along each side so that the lens's distortion
// shows as curved sides; closed.
std::vector<Eigen::Vector3d> BoardOutline(const BoardModel& board) {
  Eigen::Vector2d lo = board.corners().front().head<2>(), hi = lo;
  for (const Eigen::Vector3d& p : board.corners()) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  const Eigen::Vector2d vertices[] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}, lo};
  std::vector<Eigen::Vector3d> outline;
  const int steps = 8;
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < steps; ++k) {
      const Eigen::Vector2d p =
          vertices[side] + (vertices[side + 1] - vertices[side]) * (static_cast<double>(k) / steps);
      outline.emplace_back(p.x(), p.y(), 0.0);
    }
  }
  outline.emplace_back(lo.x(), lo.y(), 0.0);
  return outline;
}

}  // namespace

std::string DrawPlot(const GnuplotPlot& plot) {
  return RenderSvg(plot.script, plot.width_px, plot.height_px);
}

GnuplotPlot ResidualsPlot(const ValidationReport& report) {
  std::string gp;
  const size_t n = report.models.size();
  for (size_t m = 0; m < n; ++m) {
    std::string body;
    const auto& r = report.models[m].heldout;
    for (size_t k = 0; k < r.residuals.size(); ++k) {
      body +=
          fmt::format("{} {:.6g} {:.6g} {:.6g} {:.6g}\n", r.pose_ids[k],
                      DegreesFromRadians(r.residuals[k][0]), DegreesFromRadians(r.residuals[k][1]),
                      DegreesFromRadians(r.residuals[k][2]), DegreesFromRadians(r.residuals[k][3]));
    }
    gp += Block(fmt::format("r{}", m), body);
  }
  gp += fmt::format("set multiplot layout 1,{} title 'Joint residuals, {} (measured - model)'\n", n,
                    GnuplotText(EvaluatedPosesLabel(report)));
  fmt::format_to(std::back_inserter(gp),
                 "set grid\n"
                 "set key outside below horizontal font ',10'\n"
                 "set xlabel '{}'\n"
                 "set ylabel 'residual (deg)'\n"
                 "{}",
                 (report.in_sample ? "pose id (every one in-sample)" : "held-out pose id"),
                 PoseIdTics(report.heldout_ids));
  for (size_t m = 0; m < n; ++m) {
    gp += "set title " + Quoted(report.models[m].label) + "\n";
    gp += "plot ";
    for (int j = 0; j < 4; ++j) {
      gp += fmt::format("$r{} using 1:{} with linespoints pt 7 ps 0.6 lc rgb '{}' title 'q{}'{}", m,
                        j + 2, kColours[j], j + 1, j < 3 ? ", " : "\n");
    }
  }
  gp += "unset multiplot\n";
  return GnuplotPlot{.script = gp, .width_px = 360 * static_cast<int>(n), .height_px = 400};
}

GnuplotPlot HistogramPlot(const ValidationReport& report) {
  // Each model on its own axis: the a priori residuals are orders larger than Model 12's,
  // and Model 12's than Model 31's; a shared axis shows the smaller as one bar.
  std::string gp;
  const size_t n = report.models.size();
  std::vector<ResidualHistogram> histograms;
  for (size_t m = 0; m < n; ++m) {
    std::vector<double> degrees;
    for (const auto& r : report.models[m].all.residuals) {
      for (double v : r) degrees.push_back(DegreesFromRadians(v));
    }
    histograms.push_back(HistogramOf(degrees));
    std::string body;
    const ResidualHistogram& h = histograms.back();
    for (size_t b = 0; b < h.counts.size(); ++b) {
      body +=
          fmt::format("{:.6g} {}\n", h.lo + (static_cast<double>(b) + 0.5) * h.width, h.counts[b]);
    }
    gp += Block(fmt::format("h{}", m), body);
  }
  gp += fmt::format(
      "set multiplot layout 1,{} title 'Joint residuals, all joints, every pose "
      "of the dataset (each model on its own axis)'\n"
      "set grid\nset style fill solid 0.6 border -1\nset xlabel 'residual (deg)'\n"
      "set ylabel 'count'\nunset key\nset xtics rotate by -30 font ',9'\n",
      n);
  for (size_t m = 0; m < n; ++m) {
    const ResidualHistogram& h = histograms[m];
    gp += "set title " + Quoted(report.models[m].label) + "\n";
    gp += fmt::format("set xrange [{:.6g}:{:.6g}]\nset boxwidth {:.6g} absolute\n", h.lo - h.width,
                      h.hi() + h.width, h.width);
    gp += fmt::format("plot $h{} using 1:2 with boxes lc rgb '{}'\n", m, kColours[m % 5]);
  }
  gp += "unset multiplot\n";
  return GnuplotPlot{.script = gp, .width_px = 360 * static_cast<int>(n), .height_px = 360};
}

GnuplotPlot StraightnessPlot(const ValidationReport& report) {
  const size_t runs = report.models.front().straightness.size();
  std::string gp;
  for (size_t m = 0; m < report.models.size(); ++m) {
    for (size_t r = 0; r < runs; ++r) {
      const StraightnessRun& run = report.models[m].straightness[r];
      std::string body;
      for (size_t k = 0; k < run.positions.size(); ++k) {
        const double along = (run.positions[k] - run.fit.point).dot(run.fit.direction);
        body += fmt::format("{:.6g} {:.6g}\n", along * 1e3, run.fit.distances[k] * 1e3);
      }
      gp += Block(fmt::format("s{}_{}", m, r), body);
    }
  }
  gp += fmt::format(
      "set multiplot layout 1,{} title 'Straightness: distance of the FK "
      "positions to their least-squares line'\n"
      "set grid\nset key outside below horizontal font ',10'\nset xlabel 'along the line (mm)'\n"
      "set ylabel 'distance to the line (mm)'\n",
      runs);
  for (size_t r = 0; r < runs; ++r) {
    gp += fmt::format("set title 'direction {}'\nplot ", r + 1);
    for (size_t m = 0; m < report.models.size(); ++m) {
      gp += fmt::format(
          "$s{}_{} using 1:2 with linespoints pt 7 ps 0.5 lc rgb '{}' title '{} (RMS {:.3f} "
          "mm)'{}",
          m, r, kColours[m % 5], report.models[m].label,
          report.models[m].straightness[r].fit.rms_distance * 1e3,
          m + 1 < report.models.size() ? ", " : "\n");
    }
  }
  gp += "unset multiplot\n";
  return GnuplotPlot{.script = gp, .width_px = 460 * static_cast<int>(runs), .height_px = 380};
}

GnuplotPlot SquarePlot(const ValidationReport& report) {
  std::string gp;
  std::string plots;
  bool first = true;
  for (size_t m = 0; m < report.models.size(); ++m) {
    if (!report.models[m].square) continue;
    const SquareRun& run = *report.models[m].square;
    if (first) {
      std::string body;
      for (const auto& p : run.commanded)
        body += fmt::format("{:.6g} {:.6g}\n", p[0] * 1e3, p[1] * 1e3);
      body += fmt::format("{:.6g} {:.6g}\n", run.commanded[0][0] * 1e3, run.commanded[0][1] * 1e3);
      gp += Block("cmd", body);
      plots += "$cmd using 1:2 with lines lw 2 lc rgb 'black' title 'commanded'";
      first = false;
    }
    std::string body;
    for (const auto& p : run.reached)
      body += fmt::format("{:.6g} {:.6g}\n", p[0] * 1e3, p[1] * 1e3);
    body += fmt::format("{:.6g} {:.6g}\n", run.reached[0][0] * 1e3, run.reached[0][1] * 1e3);
    gp += Block(fmt::format("q{}", m), body);
    plots += fmt::format(
        ", $q{} using 1:2 with linespoints pt 7 ps 0.4 lc rgb '{}' title 'reached, {} controller "
        "(side RMS {:.2f} mm)'",
        m, kColours[m % 5], report.models[m].label, run.rms * 1e3);
  }
  gp +=
      "set title 'Square path under the Model 12 IK control law (true robot)'\n"
      "set grid\nset size ratio -1\nset key outside bottom center font ',10'\n"
      "set xlabel 'X_B (mm)' noenhanced\nset ylabel 'Y_B (mm)' noenhanced\n";
  gp += "plot " + plots + "\n";
  return GnuplotPlot{.script = gp, .width_px = 620, .height_px = 640};
}

GnuplotPlot MeasuredSquarePlot(const SquarePlan& plan, const ValidationReport& report) {
  std::string gp;
  std::string cmd;
  for (const auto& p : plan.commanded)
    cmd += fmt::format("{:.6g} {:.6g}\n", p[0] * 1e3, p[1] * 1e3);
  gp += Block("cmd", cmd);
  std::string paths = "$cmd using 1:2 with lines lw 2 lc rgb 'black' title 'commanded'";
  std::string distances;
  // Each run along the plan's path order: point k of the plan at abscissa k + 1, so that
  // runs with skipped points stay aligned.
  for (size_t m = 0; m < report.measured_squares.size(); ++m) {
    const MeasuredSquareRun& r = report.measured_squares[m];
    std::string body;
    size_t j = 0;
    for (size_t k = 0; k < plan.pose_ids.size() && j < r.run.reached.size(); ++k) {
      if (std::find(r.missing_ids.begin(), r.missing_ids.end(), plan.pose_ids[k]) !=
          r.missing_ids.end()) {
        continue;
      }
      const Eigen::Vector3d& p = r.run.reached[j];
      body += fmt::format("{} {:.6g} {:.6g} {:.6g}\n", k + 1, p[0] * 1e3, p[1] * 1e3,
                          r.run.distance[j] * 1e3);
      ++j;
    }
    gp += Block(fmt::format("m{}", m), body);
    const std::string sep = m + 1 < report.measured_squares.size() ? ", " : "";
    paths += fmt::format(
        ", $m{} using 2:3 with linespoints pt 7 ps 0.4 lc rgb '{}' title '{} controller'", m,
        kColours[m % 5], GnuplotText(r.label));
    distances += fmt::format(
        "$m{} using 1:4 with linespoints pt 7 ps 0.4 lc rgb '{}' title '{} (side RMS {:.2f} "
        "mm)'{}",
        m, kColours[m % 5], GnuplotText(r.label), r.run.rms * 1e3, sep);
  }
  gp +=
      "set multiplot layout 1,2 title 'Square path under the IK control law (Model 12 or 31), "
      "measured by the camera'\n"
      "set grid\nset key outside bottom center font ',10' noenhanced\n";
  gp +=
      "set title 'path'\nset size ratio -1\n"
      "set xlabel 'X_B (mm)' noenhanced\nset ylabel 'Y_B (mm)' noenhanced\n";
  gp += "plot " + paths + "\n";
  fmt::format_to(std::back_inserter(gp),
                 "set title 'distance to the commanded side'\n"
                 "set size noratio\n"
                 "set xlabel 'plan point (sides of {})'\n"
                 "set ylabel 'distance (mm)'\n",
                 plan.options.points_per_side);
  gp += fmt::format("set xtics {}\n", plan.options.points_per_side);
  gp += "plot " + distances + "\n";
  gp += "unset multiplot\n";
  return GnuplotPlot{.script = gp, .width_px = 1000, .height_px = 560};
}

GnuplotPlot AccuracyMapPlot(const AccuracyMap& map, const std::string& label,
                            const std::vector<EePose>& calibration_poses,
                            const std::vector<EePose>& held_out_poses) {
  const size_t levels = map.options.z_offsets_m.size();
  const size_t thetas = map.options.theta_rad.size();
  std::string gp;
  for (size_t t = 0; t < thetas; ++t) {
    for (size_t l = 0; l < levels; ++l) {
      std::string body;
      for (const AccuracyMapPoint& point : map.points) {
        if (point.x[2] != map.centre[2] + map.options.z_offsets_m[l] ||
            point.x[3] != map.options.theta_rad[t]) {
          continue;
        }
        body += fmt::format("{:.6g} {:.6g} {:.6g}\n", (point.x[0] - map.centre[0]) * 1e3,
                            (point.x[1] - map.centre[1]) * 1e3, point.position_sigma_m * 1e3);
      }
      if (body.empty()) body += "NaN NaN NaN\n";  // a panel out of reach stays empty
      gp += Block(fmt::format("m{}_{}", t, l), body);
      gp += Block(fmt::format("c{}_{}", t, l), PosesInPanel(map, calibration_poses, t, l));
      gp += Block(fmt::format("e{}_{}", t, l), PosesInPanel(map, held_out_poses, t, l));
    }
  }
  const double extent = map.options.half_extent_m * 1e3 + map.options.step_m * 1e3;
  gp += fmt::format(
      "set multiplot layout {},{} title '{}: predicted 1-sigma position error (mm); the "
      "dataset''s poses in the panel of their nearest Z and theta'\n",
      thetas, levels, GnuplotText(label));
  gp += fmt::format("set xrange [{0}:{1}]\nset yrange [{0}:{1}]\nset size ratio -1\n", -extent,
                    extent);
  gp += fmt::format("set cbrange [0:{:.6g}]\nset palette rgbformulae 22,13,-31\n",
                    std::max(map.MaxPositionSigma() * 1e3, 1e-9));
  // Labels of 11 px at the page's 1:1 scale (the report's column is 1200 px, three panels
  // of 400 px): 8 px was too small to read (issue 43 point 8).
  gp +=
      "set key outside below horizontal font ',11' samplen 1\nset tics font ',11'\n"
      "set xlabel 'X - centre (mm)' font ',11'\nset ylabel 'Y - centre (mm)' font ',11'\n";
  for (size_t t = 0; t < thetas; ++t) {
    for (size_t l = 0; l < levels; ++l) {
      gp += fmt::format("set title 'Z {:+.0f} mm, theta {:+.0f} deg' font ',12'\n",
                        map.options.z_offsets_m[l] * 1e3,
                        DegreesFromRadians(map.options.theta_rad[t]));
      gp += fmt::format(
          "plot $m{0}_{1} using 1:2:3 with points pt 5 ps 1.3 lc palette notitle, $c{0}_{1} "
          "using 1:2 with points pt 6 ps 0.9 lw 1.5 lc rgb 'black' title 'calibration pose'",
          t, l);
      if (!held_out_poses.empty()) {
        gp += fmt::format(
            ", $e{}_{} using 1:2 with points pt 2 ps 0.9 lw 1.5 lc rgb '#d62728' title "
            "'held-out pose'",
            t, l);
      }
      gp += "\n";
    }
  }
  gp += "unset multiplot\n";
  return GnuplotPlot{.script = gp,
                     .width_px = 400 * static_cast<int>(levels),
                     .height_px = 400 * static_cast<int>(thetas)};
}

GnuplotPlot CornerResidualPlot(const CornerResidualMap& map) {
  const double cell_w = static_cast<double>(map.width) / map.columns;
  const double cell_h = static_cast<double>(map.height) / map.rows;
  double largest_mean = 0.0, largest_rms = 0.0;
  for (const CornerResidualCell& cell : map.cells) {
    largest_mean = std::max(largest_mean, cell.mean_px.norm());
    largest_rms = std::max(largest_rms, cell.rms_px);
  }
  const double scale = largest_mean > 0.0 ? 0.9 * std::min(cell_w, cell_h) / largest_mean : 1.0;
  std::string cells, arrows;
  for (const CornerResidualCell& cell : map.cells) {
    if (cell.corners == 0) continue;
    const double u = (cell.column + 0.5) * cell_w, v = (cell.row + 0.5) * cell_h;
    cells += fmt::format("{:.6g} {:.6g} {:.6g} {:.6g} {:.6g}\n", u, v, 0.5 * cell_w, 0.5 * cell_h,
                         cell.rms_px);
    arrows += fmt::format("{:.6g} {:.6g} {:.6g} {:.6g}\n", u, v, scale * cell.mean_px.x(),
                          scale * cell.mean_px.y());
  }
  std::string gp;
  gp += Block("cells", cells) + Block("arrows", arrows);
  gp += fmt::format(
      "set title 'Corner residuals over the image: colour, RMS per axis (px); arrows, the "
      "cell mean x {:.0f}'\n",
      scale);
  gp += fmt::format("set xrange [0:{0}]\nset yrange [{1}:0]\nset size ratio -1\n", map.width,
                    map.height);
  gp += fmt::format("set cbrange [0:{:.6g}]\nset palette rgbformulae 22,13,-31\n",
                    std::max(largest_rms, 1e-9));
  gp += "unset key\nset xlabel 'u (px)'\nset ylabel 'v (px)'\nset cblabel 'px'\n";
  gp +=
      "plot $cells using 1:2:3:4:5 with boxxyerror fs solid 1.0 noborder lc palette, "
      "$arrows using 1:2:3:4 with vectors head filled size screen 0.008,20 lw 1.5 lc rgb "
      "'black'\n";
  return GnuplotPlot{.script = gp, .width_px = 760, .height_px = 600};
}

GnuplotPlot BoardCoveragePlot(const std::vector<DatasetRow>& rows,
                              const std::vector<int64_t>& held_out_ids, const BoardModel& board,
                              const CameraIntrinsics& camera) {
  const CameraModel lens(camera);
  const std::vector<Eigen::Vector3d> outline_T = BoardOutline(board);
  Eigen::Vector3d lo_T = outline_T.front(), hi_T = lo_T;
  for (const Eigen::Vector3d& p : outline_T) {
    lo_T = lo_T.cwiseMin(p);
    hi_T = hi_T.cwiseMax(p);
  }
  const Eigen::Vector3d centre_T = 0.5 * (lo_T + hi_T);
  std::string outlines[2], centres[2];  // calibration, held out
  for (const DatasetRow& row : rows) {
    const bool held_out =
        std::find(held_out_ids.begin(), held_out_ids.end(), row.pose_id) != held_out_ids.end();
    Eigen::Vector2d uv;
    if (!lens.Project(row.X_CT * centre_T, &uv)) continue;  // behind the camera
    centres[held_out] += fmt::format("{:.6g} {:.6g}\n", uv.x(), uv.y());
    for (const Eigen::Vector3d& p_TQ : outline_T) {
      if (lens.Project(row.X_CT * p_TQ, &uv)) {
        outlines[held_out] += fmt::format("{:.6g} {:.6g}\n", uv.x(), uv.y());
      }
    }
    outlines[held_out] += "\n";  // a blank line ends one outline
  }
  std::string gp;
  const char* names[] = {"calib", "valid"};
  for (int s = 0; s < 2; ++s) {
    gp += Block(fmt::format("{}_outlines", names[s]),
                outlines[s].empty() ? "NaN NaN\n" : outlines[s]);
    gp += Block(fmt::format("{}_centres", names[s]), centres[s].empty() ? "NaN NaN\n" : centres[s]);
  }
  gp += fmt::format(
      "set title 'Where the board fell in the {}x{} image, every pose of the dataset'\n"
      "set xrange [0:{}]\nset yrange [{}:0]\nset size ratio -1\nset grid\n"
      "set key outside below horizontal font ',10'\nset xlabel 'u (px)'\nset ylabel 'v (px)'\n",
      camera.width, camera.height, camera.width, camera.height);
  gp +=
      "plot $calib_outlines using 1:2 with lines lw 0.8 lc rgb '#1f77b4' title 'calibration "
      "pose (board outline)', $calib_centres using 1:2 with points pt 7 ps 0.5 lc rgb "
      "'#1f77b4' notitle";
  if (!held_out_ids.empty()) {
    gp +=
        ", $valid_outlines using 1:2 with lines lw 1.2 dt 2 lc rgb '#d62728' title 'held-out "
        "pose (board outline)', $valid_centres using 1:2 with points pt 7 ps 0.6 lc rgb "
        "'#d62728' notitle";
  }
  gp += "\n";
  const int width = 760;
  return GnuplotPlot{
      .script = gp,
      .width_px = width,
      .height_px = std::max(300, width * camera.height / std::max(camera.width, 1) + 80)};
}

}  // namespace h4::host
