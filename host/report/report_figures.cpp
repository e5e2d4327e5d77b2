// gnuplot scripts of the report's figures (see report_figures.h). Data go inline as
// gnuplot data blocks; values are converted to deg and mm for reading, as in the tables.
#include "host/report/report_figures.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <spdlog/fmt/fmt.h>

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

}  // namespace

std::string ResidualsFigure(const ValidationReport& report) {
  std::ostringstream gp;
  const size_t n = report.models.size();
  for (size_t m = 0; m < n; ++m) {
    std::ostringstream body;
    const auto& r = report.models[m].heldout;
    for (size_t k = 0; k < r.residuals.size(); ++k) {
      body << fmt::format(
          "{} {:.6g} {:.6g} {:.6g} {:.6g}\n", k + 1, DegreesFromRadians(r.residuals[k][0]),
          DegreesFromRadians(r.residuals[k][1]), DegreesFromRadians(r.residuals[k][2]),
          DegreesFromRadians(r.residuals[k][3]));
    }
    gp << Block(fmt::format("r{}", m), body.str());
  }
  gp << fmt::format("set multiplot layout 1,{} title 'Joint residuals, {} (measured - model)'\n", n,
                    GnuplotText(EvaluatedPosesLabel(report)));
  gp << "set grid\nset key top right font ',10'\nset xlabel '"
     << (report.in_sample ? "pose (every one in-sample)" : "held-out pose")
     << "'\nset ylabel 'residual (deg)'\n";
  for (size_t m = 0; m < n; ++m) {
    gp << "set title " << Quoted(report.models[m].label) << "\n";
    gp << "plot ";
    for (int j = 0; j < 4; ++j) {
      gp << fmt::format("$r{} using 1:{} with linespoints pt 7 ps 0.6 lc rgb '{}' title 'q{}'{}", m,
                        j + 2, kColours[j], j + 1, j < 3 ? ", " : "\n");
    }
  }
  gp << "unset multiplot\n";
  return RenderSvg(gp.str(), 360 * static_cast<int>(n), 380);
}

std::string HistogramFigure(const ValidationReport& report) {
  // Identified models only: the a priori residuals are two orders larger.
  double extent = 0.0;
  for (size_t m = 1; m < report.models.size(); ++m) {
    for (const auto& r : report.models[m].all.residuals) {
      for (double v : r) extent = std::max(extent, std::abs(DegreesFromRadians(v)));
    }
  }
  if (extent <= 0.0) extent = 1.0;
  const int bins = 25;
  const double width = 2.0 * extent / bins;
  std::ostringstream gp;
  const size_t n = report.models.size();
  for (size_t m = 0; m < n; ++m) {
    std::vector<int> counts(bins, 0);
    double local_extent = 0.0;
    for (const auto& r : report.models[m].all.residuals) {
      for (double v : r) local_extent = std::max(local_extent, std::abs(DegreesFromRadians(v)));
    }
    const double w = m == 0 ? 2.0 * std::max(local_extent, 1e-9) / bins : width;
    const double lo = m == 0 ? -std::max(local_extent, 1e-9) : -extent;
    for (const auto& r : report.models[m].all.residuals) {
      for (double v : r) {
        const int b =
            std::clamp(static_cast<int>(std::floor((DegreesFromRadians(v) - lo) / w)), 0, bins - 1);
        ++counts[b];
      }
    }
    std::ostringstream body;
    for (int b = 0; b < bins; ++b)
      body << fmt::format("{:.6g} {}\n", lo + (b + 0.5) * w, counts[b]);
    gp << Block(fmt::format("h{}", m), body.str());
  }
  gp << fmt::format(
      "set multiplot layout 1,{} title 'Joint residuals, all joints, every pose "
      "of the dataset'\n",
      n);
  gp << "set grid\nset style fill solid 0.6 border -1\nset xlabel 'residual (deg)'\n"
        "set ylabel 'count'\nunset key\n";
  for (size_t m = 0; m < n; ++m) {
    gp << "set title " << Quoted(report.models[m].label) << "\n";
    gp << fmt::format("plot $h{} using 1:2 with boxes lc rgb '{}'\n", m, kColours[m % 5]);
  }
  gp << "unset multiplot\n";
  return RenderSvg(gp.str(), 360 * static_cast<int>(n), 340);
}

std::string StraightnessFigure(const ValidationReport& report) {
  const size_t runs = report.models.front().straightness.size();
  std::ostringstream gp;
  for (size_t m = 0; m < report.models.size(); ++m) {
    for (size_t r = 0; r < runs; ++r) {
      const StraightnessRun& run = report.models[m].straightness[r];
      std::ostringstream body;
      for (size_t k = 0; k < run.positions.size(); ++k) {
        const double along = (run.positions[k] - run.fit.point).dot(run.fit.direction);
        body << fmt::format("{:.6g} {:.6g}\n", along * 1e3, run.fit.distances[k] * 1e3);
      }
      gp << Block(fmt::format("s{}_{}", m, r), body.str());
    }
  }
  gp << fmt::format(
      "set multiplot layout 1,{} title 'Straightness: distance of the FK "
      "positions to their least-squares line'\n",
      runs);
  gp << "set grid\nset key top left font ',10'\nset xlabel 'along the line (mm)'\n"
        "set ylabel 'distance to the line (mm)'\n";
  for (size_t r = 0; r < runs; ++r) {
    gp << fmt::format("set title 'direction {}'\nplot ", r + 1);
    for (size_t m = 0; m < report.models.size(); ++m) {
      gp << fmt::format(
          "$s{}_{} using 1:2 with linespoints pt 7 ps 0.5 lc rgb '{}' title '{} (RMS {:.3f} "
          "mm)'{}",
          m, r, kColours[m % 5], report.models[m].label,
          report.models[m].straightness[r].fit.rms_distance * 1e3,
          m + 1 < report.models.size() ? ", " : "\n");
    }
  }
  gp << "unset multiplot\n";
  return RenderSvg(gp.str(), 460 * static_cast<int>(runs), 380);
}

std::string SquareFigure(const ValidationReport& report) {
  std::ostringstream gp;
  std::string plots;
  bool first = true;
  for (size_t m = 0; m < report.models.size(); ++m) {
    if (!report.models[m].square) continue;
    const SquareRun& run = *report.models[m].square;
    if (first) {
      std::ostringstream body;
      for (const auto& p : run.commanded)
        body << fmt::format("{:.6g} {:.6g}\n", p[0] * 1e3, p[1] * 1e3);
      body << fmt::format("{:.6g} {:.6g}\n", run.commanded[0][0] * 1e3, run.commanded[0][1] * 1e3);
      gp << Block("cmd", body.str());
      plots += "$cmd using 1:2 with lines lw 2 lc rgb 'black' title 'commanded'";
      first = false;
    }
    std::ostringstream body;
    for (const auto& p : run.reached)
      body << fmt::format("{:.6g} {:.6g}\n", p[0] * 1e3, p[1] * 1e3);
    body << fmt::format("{:.6g} {:.6g}\n", run.reached[0][0] * 1e3, run.reached[0][1] * 1e3);
    gp << Block(fmt::format("q{}", m), body.str());
    plots += fmt::format(
        ", $q{} using 1:2 with linespoints pt 7 ps 0.4 lc rgb '{}' title 'reached, {} controller "
        "(side RMS {:.2f} mm)'",
        m, kColours[m % 5], report.models[m].label, run.rms * 1e3);
  }
  gp << "set title 'Square path under the Model 12 IK control law (true robot)'\n"
        "set grid\nset size ratio -1\nset key outside bottom center font ',10'\n"
        "set xlabel 'X_B (mm)' noenhanced\nset ylabel 'Y_B (mm)' noenhanced\n";
  gp << "plot " << plots << "\n";
  return RenderSvg(gp.str(), 620, 640);
}

std::string MeasuredSquareFigure(const SquarePlan& plan, const ValidationReport& report) {
  std::ostringstream gp;
  std::ostringstream cmd;
  for (const auto& p : plan.commanded)
    cmd << fmt::format("{:.6g} {:.6g}\n", p[0] * 1e3, p[1] * 1e3);
  gp << Block("cmd", cmd.str());
  std::string paths = "$cmd using 1:2 with lines lw 2 lc rgb 'black' title 'commanded'";
  std::string distances;
  // Each run along the plan's path order: point k of the plan at abscissa k + 1, so that
  // runs with skipped points stay aligned.
  for (size_t m = 0; m < report.measured_squares.size(); ++m) {
    const MeasuredSquareRun& r = report.measured_squares[m];
    std::ostringstream body;
    size_t j = 0;
    for (size_t k = 0; k < plan.pose_ids.size() && j < r.run.reached.size(); ++k) {
      if (std::find(r.missing_ids.begin(), r.missing_ids.end(), plan.pose_ids[k]) !=
          r.missing_ids.end()) {
        continue;
      }
      const Eigen::Vector3d& p = r.run.reached[j];
      body << fmt::format("{} {:.6g} {:.6g} {:.6g}\n", k + 1, p[0] * 1e3, p[1] * 1e3,
                          r.run.distance[j] * 1e3);
      ++j;
    }
    gp << Block(fmt::format("m{}", m), body.str());
    const std::string sep = m + 1 < report.measured_squares.size() ? ", " : "";
    paths += fmt::format(
        ", $m{} using 2:3 with linespoints pt 7 ps 0.4 lc rgb '{}' title '{} controller'", m,
        kColours[m % 5], GnuplotText(r.label));
    distances += fmt::format(
        "$m{} using 1:4 with linespoints pt 7 ps 0.4 lc rgb '{}' title '{} (side RMS {:.2f} "
        "mm)'{}",
        m, kColours[m % 5], GnuplotText(r.label), r.run.rms * 1e3, sep);
  }
  gp << "set multiplot layout 1,2 title 'Square path under the IK control law (Model 12 or 31), "
        "measured by the camera'\n"
        "set grid\nset key outside bottom center font ',10' noenhanced\n";
  gp << "set title 'path'\nset size ratio -1\n"
        "set xlabel 'X_B (mm)' noenhanced\nset ylabel 'Y_B (mm)' noenhanced\n";
  gp << "plot " << paths << "\n";
  gp << "set title 'distance to the commanded side'\nset size noratio\n"
        "set xlabel 'plan point (sides of "
     << plan.options.points_per_side
     << ")'\n"
        "set ylabel 'distance (mm)'\n";
  gp << fmt::format("set xtics {}\n", plan.options.points_per_side);
  gp << "plot " << distances << "\n";
  gp << "unset multiplot\n";
  return RenderSvg(gp.str(), 1000, 560);
}

std::string AccuracyMapFigure(const AccuracyMap& map, const std::string& label) {
  const size_t levels = map.options.z_offsets_m.size();
  const size_t thetas = map.options.theta_rad.size();
  std::ostringstream gp;
  for (size_t t = 0; t < thetas; ++t) {
    for (size_t l = 0; l < levels; ++l) {
      std::ostringstream body;
      for (const AccuracyMapPoint& point : map.points) {
        if (point.x[2] != map.centre[2] + map.options.z_offsets_m[l] ||
            point.x[3] != map.options.theta_rad[t]) {
          continue;
        }
        body << fmt::format("{:.6g} {:.6g} {:.6g}\n", (point.x[0] - map.centre[0]) * 1e3,
                            (point.x[1] - map.centre[1]) * 1e3, point.position_sigma_m * 1e3);
      }
      if (body.str().empty()) body << "NaN NaN NaN\n";  // a panel out of reach stays empty
      gp << Block(fmt::format("m{}_{}", t, l), body.str());
    }
  }
  const double extent = map.options.half_extent_m * 1e3 + map.options.step_m * 1e3;
  gp << fmt::format(
      "set multiplot layout {},{} title '{}: predicted 1-sigma position error (mm)'\n", thetas,
      levels, GnuplotText(label));
  gp << fmt::format("set xrange [{0}:{1}]\nset yrange [{0}:{1}]\nset size ratio -1\n",
                    -extent, extent);
  gp << fmt::format("set cbrange [0:{:.6g}]\nset palette rgbformulae 22,13,-31\n",
                    std::max(map.MaxPositionSigma() * 1e3, 1e-9));
  gp << "unset key\nset tics font ',8'\nset xlabel 'X - centre (mm)' font ',8'\n"
        "set ylabel 'Y - centre (mm)' font ',8'\n";
  for (size_t t = 0; t < thetas; ++t) {
    for (size_t l = 0; l < levels; ++l) {
      gp << fmt::format("set title 'Z {:+.0f} mm, theta {:+.0f} deg' font ',9'\n",
                        map.options.z_offsets_m[l] * 1e3,
                        DegreesFromRadians(map.options.theta_rad[t]));
      gp << fmt::format("plot $m{}_{} using 1:2:3 with points pt 5 ps 1.3 lc palette\n", t, l);
    }
  }
  gp << "unset multiplot\n";
  return RenderSvg(gp.str(), 300 * static_cast<int>(levels), 280 * static_cast<int>(thetas));
}

std::string CornerResidualFigure(const CornerResidualMap& map) {
  const double cell_w = static_cast<double>(map.width) / map.columns;
  const double cell_h = static_cast<double>(map.height) / map.rows;
  double largest_mean = 0.0, largest_rms = 0.0;
  for (const CornerResidualCell& cell : map.cells) {
    largest_mean = std::max(largest_mean, cell.mean_px.norm());
    largest_rms = std::max(largest_rms, cell.rms_px);
  }
  const double scale = largest_mean > 0.0 ? 0.9 * std::min(cell_w, cell_h) / largest_mean : 1.0;
  std::ostringstream cells, arrows;
  for (const CornerResidualCell& cell : map.cells) {
    if (cell.corners == 0) continue;
    const double u = (cell.column + 0.5) * cell_w, v = (cell.row + 0.5) * cell_h;
    cells << fmt::format("{:.6g} {:.6g} {:.6g} {:.6g} {:.6g}\n", u, v, 0.5 * cell_w, 0.5 * cell_h,
                         cell.rms_px);
    arrows << fmt::format("{:.6g} {:.6g} {:.6g} {:.6g}\n", u, v, scale * cell.mean_px.x(),
                          scale * cell.mean_px.y());
  }
  std::ostringstream gp;
  gp << Block("cells", cells.str()) << Block("arrows", arrows.str());
  gp << fmt::format(
      "set title 'Corner residuals over the image: colour, RMS per axis (px); arrows, the "
      "cell mean x {:.0f}'\n",
      scale);
  gp << fmt::format("set xrange [0:{0}]\nset yrange [{1}:0]\nset size ratio -1\n", map.width,
                    map.height);
  gp << fmt::format("set cbrange [0:{:.6g}]\nset palette rgbformulae 22,13,-31\n",
                    std::max(largest_rms, 1e-9));
  gp << "unset key\nset xlabel 'u (px)'\nset ylabel 'v (px)'\nset cblabel 'px'\n";
  gp << "plot $cells using 1:2:3:4:5 with boxxyerror fs solid 1.0 noborder lc palette, "
        "$arrows using 1:2:3:4 with vectors head filled size screen 0.008,20 lw 1.5 lc rgb "
        "'black'\n";
  return RenderSvg(gp.str(), 760, 600);
}

}  // namespace h4::host
