// The report page (see html_report.h): sections in kReportSections order, inline CSS, the
// gnuplot SVG figures inlined, no script. Every figure is drawn before anything is written,
// so a failure leaves no half report.
#include "host/report/html_report.h"

#include <filesystem>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <vector>

#include <spdlog/fmt/fmt.h>

#include "common/formats/file_output.h"
#include "common/text/markup_escape.h"
#include "host/report/pose_residuals.h"
#include "host/report/report_camera.h"
#include "host/report/report_figures.h"
#include "host/report/report_tables.h"
#include "host/report/report_verdict.h"

namespace h4::host {
namespace {

constexpr const char* kStyle = R"(
body { font-family: "DejaVu Sans", sans-serif; margin: 2em auto; max-width: 1200px;
       color: #222; line-height: 1.4; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: right; }
th:first-child { text-align: left; } tr.paper { background: #fff6dd; }
tr.fixed { color: #777; } tr.measured { background: #eef6ff; } figure { margin: 1em 0; } figure svg { max-width: 100%; height: auto; }
code { background: #f3f3f3; padding: 0 0.2em; } .note { color: #a33; }
.not-applicable { color: #555; font-style: italic; }
table.rejected td:last-child { text-align: left; }
.verdict-good { background: #e6f6e6; padding: 0.5em; } .verdict-bad { background: #fde8e8; padding: 0.5em; }
)";

std::string Section(const std::string& id, const std::string& title, const std::string& body) {
  return fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", id, title, body);
}

// The report's sections in order, and their table of contents.
class Sections {
 public:
  void Add(const std::string& id, const std::string& title, const std::string& body) {
    html_ += Section(id, title, body);
    contents_ += fmt::format("<li><a href=\"#{}\">{}</a></li>\n", id, title);
  }
  std::string TableOfContents() const {
    return "<nav id=\"contents\">\n<h2>Contents</h2>\n<ol>\n" + contents_ + "</ol>\n</nav>\n";
  }
  const std::string& Html() const { return html_; }

 private:
  std::string html_;
  std::string contents_;
};

std::string Figure(const std::string& svg, const std::string& caption) {
  return "<figure>\n" + svg + "\n<figcaption>" + caption + "</figcaption>\n</figure>\n";
}

// A section that does not apply to these inputs: said in neutral words (nothing is wrong),
// with what would fill it.
std::string NotComputed(const std::string& why) {
  return "<p class=\"not-applicable\">Not computed: " + MarkupEscape(why) + "</p>\n";
}

}  // namespace

namespace {

// Every figure, drawn before anything is written: if gnuplot fails, nothing is.
struct DrawnFigures {
  bool has_straightness = false, has_square = false, has_measured = false;
  std::string residuals, histograms, straightness, square, measured_square;
  /// One per identified model that has one: its label and figure.
  std::vector<std::pair<std::string, std::string>> accuracy_maps;
  std::string corner_residuals;  ///< empty without corners
  std::string board_coverage;    ///< empty without the camera and board
};

DrawnFigures DrawFigures(const ValidationInputs& in, const ValidationReport& report) {
  DrawnFigures f;
  f.has_straightness = !report.models.front().straightness.empty();
  for (const auto& v : report.models) f.has_square = f.has_square || v.square.has_value();
  f.has_measured = !report.measured_squares.empty() && in.square_plan.has_value();
  f.residuals = DrawPlot(ResidualsPlot(report));
  f.histograms = DrawPlot(HistogramPlot(report));
  if (f.has_straightness) f.straightness = DrawPlot(StraightnessPlot(report));
  if (f.has_square) f.square = DrawPlot(SquarePlot(report));
  if (f.has_measured) f.measured_square = DrawPlot(MeasuredSquarePlot(*in.square_plan, report));
  for (const auto& v : report.models) {
    if (!v.accuracy_map) continue;
    f.accuracy_maps.emplace_back(
        v.label, DrawPlot(AccuracyMapPlot(*v.accuracy_map, v.label, v.calibration_poses,
                                          v.evaluated_poses)));
  }
  if (report.corner_residuals) {
    f.corner_residuals = DrawPlot(CornerResidualPlot(*report.corner_residuals));
  }
  if (in.camera && in.board) {
    const std::vector<int64_t> held_out =
        report.in_sample ? std::vector<int64_t>{} : report.heldout_ids;
    f.board_coverage = DrawPlot(BoardCoveragePlot(in.rows, held_out, *in.board, *in.camera));
  }
  return f;
}

std::string AccuracyMapFileName(ModelKind model) {
  return fmt::format("accuracy_map_model{}.csv", ToString(model));
}

// The accuracy map's figure and table, or why there is none.
std::string AccuracyMapSection(const ValidationReport& report, const DrawnFigures& f) {
  if (f.accuracy_maps.empty()) {
    return NotComputed("no identified result with a parameter covariance (see the notes)");
  }
  // In-sample, every evaluated pose is a calibration one: no crosses.
  const std::string poses = report.in_sample
                                ? "circles, the poses the calibration used"
                                : "circles, the poses the calibration used; crosses, the "
                                  "held-out ones";
  std::string figures;
  for (const auto& [label, svg] : f.accuracy_maps) {
    figures += Figure(svg, MarkupEscape(label) +
                               ": each square a commanded pose of the grid, empty where out of "
                               "reach; " +
                               poses +
                               " (where the model puts their joint readings). Each figure has "
                               "its own colour scale.");
  }
  return "<p>The predicted one-sigma position error of the calibrated robot commanded "
         "through the identified model, from the uncertainty of its parameters, over its "
         "workspace: where it is high, the calibration holds less and more poses there help "
         "(<code>h4cal plan</code>). Written as CSV beside this page "
         "(<code>accuracy_map_model12.csv</code>, <code>accuracy_map_model31.csv</code>).</p>\n" +
         figures + AccuracyMapTable(report);
}

// The camera section: refined intrinsics, where the model misfits, its share of the map;
// one line when the report knows nothing of the camera.
std::string CameraSection(const ValidationInputs& in, const ValidationReport& report,
                          const DrawnFigures& f) {
  const std::string refined = RefinedIntrinsicsTable(in);
  const std::string share = CameraShareTable(report);
  if (refined.empty() && share.empty() && !report.corner_residuals) {
    return NotComputed(
        "the results come from the pose path, which takes the camera file's intrinsics as "
        "exact, and no corners were given: identify --corners --board --camera refines the "
        "intrinsics with the robot; validate --corners --board --camera maps the corner "
        "residuals and draws where the board fell in the image");
  }
  std::string html =
      "<p>Every board pose is measured through the camera file's intrinsics; an error in them "
      "is shared by every pose, so residuals against the same camera do not show it "
      "(common/README.md, \"The camera file's uncertainty\").</p>\n<h3>Intrinsics</h3>\n";
  html += refined.empty() ? NotComputed(
                                "no result comes from the corner path (identify "
                                "--corners): the camera file's intrinsics were taken "
                                "as given")
                          : refined;
  html += "<h3>Where the camera model misfits</h3>\n";
  if (report.corner_residuals) {
    html += Figure(f.corner_residuals,
                   "Each corner measured by the camera against its prediction from the "
                   "joint readings, binned over the image. A model that fits leaves noise "
                   "alike everywhere; a pattern (arrows turning about the centre, growing "
                   "towards the edges, or all one way) is the camera model's misfit.") +
            CornerResidualSummary(*report.corner_residuals);
  } else {
    html += NotComputed("no corners given (--corners, --board, --camera)");
  }
  html += "<h3>The board's coverage of the image</h3>\n";
  html += f.board_coverage.empty()
              ? NotComputed(
                    "the camera file and board are not given (--corners, --board, "
                    "--camera)")
              : Figure(f.board_coverage,
                       "Each pose's board, the rectangle around its corners, projected from "
                       "its measured pose X_CT through the camera file: corners seen only "
                       "near the centre leave the distortion at the edges unmeasured.");
  html += "<h3>The camera model's share of the accuracy map</h3>\n";
  html += share.empty()
              ? NotComputed(
                    "no result says how much the camera's uncertainty adds (its "
                    "parameter_covariance_camera_exact: the corner path, or identify "
                    "--camera with a file that has an intrinsics_covariance)")
              : "<p>The accuracy map's predicted 1-sigma position error, the same with the "
                "intrinsics known exactly, and the camera model's share (per pose, the root "
                "of the difference of the variances).</p>\n" +
                    share;
  return html;
}

// Everything after the verdict, in order.
Sections DetailSections(const ValidationInputs& in, const ValidationReport& report,
                        const DrawnFigures& f) {
  Sections sections;
  sections.Add("summary", "Summary", SummaryTable(in, report));
  sections.Add("parameters", "Parameters", ParameterTables(in));
  sections.Add("identifiability", "Identifiability", IdentifiabilityTable(in));
  sections.Add("table2", "Table 2: Model 12 parameters", Table2(in, report));
  const std::string poses = EvaluatedPosesLabel(report);
  sections.Add("table3", "Table 3: joint residuals, " + poses, Table3(report));
  sections.Add("positioning", "Positioning error", PositioningTable(report));
  sections.Add("accuracy-map", "Accuracy map", AccuracyMapSection(report, f));
  sections.Add("camera", "Camera model", CameraSection(in, report, f));
  sections.Add("residuals", "Residuals per pose and joint",
               Figure(f.residuals, "Each pose, " + poses + ", before and after calibration.") +
                   PoseResidualsTable(report));
  sections.Add("histograms", "Residual histograms",
               Figure(f.histograms, "All joints, every pose of the dataset."));
  sections.Add("table4", "Table 4: straightness",
               f.has_straightness
                   ? Table4(report)
                   : NotComputed("optional: no ruler run given (the paper's straightness test, "
                                 "validate --straightness)"));
  sections.Add("straightness", "Straightness runs",
               f.has_straightness ? Figure(f.straightness, "Distance to the fitted line.")
                                  : NotComputed("optional: no ruler run given"));
  sections.Add("square", "Square path",
               f.has_square || f.has_measured
                   ? SquareTable(in, report)
                   : NotComputed("optional: needs square runs measured on the robot "
                                 "(--square-measured), or the true robot of a simulation"));
  sections.Add("square-plot", "Square path plot",
               f.has_square ? Figure(f.square, "Commanded and reached paths in the X-Y plane.")
                            : NotComputed("drawn for a simulation only: needs the true "
                                          "robot (its truth file)"));
  if (f.has_measured) {
    sections.Add(kMeasuredSquareSection, "Square path measured by the camera",
                 Figure(f.measured_square,
                        "Commanded and measured paths in the X-Y plane of B, and each "
                        "measured point's distance to its commanded side."));
  }
  sections.Add("four-dof", "4-DoF check", FourDofTable(report));
  std::string notes;
  for (const auto& note : report.notes) notes += "<li>" + MarkupEscape(note) + "</li>\n";
  sections.Add("notes", "Notes", notes.empty() ? "<p>None.</p>\n" : "<ul>\n" + notes + "</ul>\n");
  return sections;
}

}  // namespace

std::string FormatHtmlReport(const ValidationInputs& in, const ValidationReport& report,
                             const std::string& command) {
  if (report.models.empty()) throw std::invalid_argument("nothing to report: no model validated");
  const Sections sections = DetailSections(in, report, DrawFigures(in, report));

  // The verdict and the figures that decide it first (with each result's version, date and
  // inputs), then how the report was made, the contents, the details.
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<title>h4cal calibration report</title>\n<style>{}</style>\n"
      "</head>\n<body>\n<h1>H4 calibration report</h1>\n",
      kStyle);
  html += Section("verdict", "Verdict", VerdictSection(in));
  fmt::format_to(std::back_inserter(html),
                 "<p>Validation after Renaud et al., ICRA 2003, section IV.D. Made by "
                 "<code>{}</code>.{} Lengths in mm and angles in deg, except the paper's Tables "
                 "2-4, in its m and rad.</p>\n",
                 MarkupEscape(command),
                 report.paper_scenario
                     ? " <strong>Paper scenario</strong>: the paper's published numbers (rows "
                       "marked paper) stand beside ours."
                     : "");
  html += sections.TableOfContents() + sections.Html();
  html += "</body>\n</html>\n";
  return html;
}

std::string WriteHtmlReport(const std::string& dir, const ValidationInputs& inputs,
                            const ValidationReport& report, const std::string& command) {
  const std::string html = FormatHtmlReport(inputs, report, command);
  std::filesystem::create_directories(dir);
  const std::string path = (std::filesystem::path(dir) / "report.html").string();
  WriteFileAtomically(path, html);
  WriteFileAtomically((std::filesystem::path(dir) / "residuals.csv").string(),
                      PoseResidualsCsv(report));
  for (const ModelValidation& v : report.models) {
    if (!v.accuracy_map) continue;
    WriteFileAtomically(
        (std::filesystem::path(dir) / AccuracyMapFileName(v.accuracy_map->model)).string(),
        AccuracyMapCsv(*v.accuracy_map));
  }
  return path;
}

}  // namespace h4::host
