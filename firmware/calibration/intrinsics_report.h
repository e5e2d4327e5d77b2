// What an intrinsics calibration shows a technician, after mrcal's reports: each parameter
// with its 1-sigma, where in the image the corners fell (the coverage picture and the
// empty cells of a grid over the image), and the residuals (magnified vectors over the
// image, magnitude against the distance from the principal point, and a histogram). Pure:
// a result in, numbers and the text of SVG and HTML files out; the command writes them
// (calibrate_intrinsics_command.cpp).
#pragma once

#include <string>
#include <vector>

#include "firmware/calibration/intrinsics_calibration.h"

namespace h4::cam {

/// One calibrated parameter: fx, fy, cx, cy (px), then the distortion coefficients.
struct ParameterRow {
  std::string name;
  double value = 0;
  double sigma = 0;        ///< 1-sigma (intrinsics_covariance), 0 when unknown
  bool has_sigma = false;  ///< whether the calibration gave a covariance
  std::string unit;        ///< "px" or "" (distortion coefficients)
};

std::vector<ParameterRow> ParameterRows(const IntrinsicsCalibrationResult& result);

/// How many corners of the used views fell in each cell of a cols x rows grid over the
/// image.
struct CoverageGrid {
  int cols = 0;
  int rows = 0;
  int width = 0;  ///< image, px
  int height = 0;
  std::vector<int> corners;  ///< per cell, row-major
  int EmptyCells() const;
  int CellOf(double u, double v) const;  ///< row-major index of the cell of pixel (u, v)
};

CoverageGrid CornerCoverage(const IntrinsicsCalibrationResult& result, int cols = 8, int rows = 6);

/// "corners in 46 of 48 cells of the 8 x 6 grid over the image; empty: row 0 col 7, row 5
/// col 0 (rows from the top)".
std::string CoverageSummary(const CoverageGrid& grid);

/// Residual statistics of the used views: every residual's length, px, and the distance
/// of its corner from the principal point, px.
struct ResidualSamples {
  std::vector<double> length_px;
  std::vector<double> radius_px;
  std::vector<double> components_px;  ///< x and y of every residual
};

ResidualSamples CollectResiduals(const IntrinsicsCalibrationResult& result);

/// Counts of `values` in `bins` equal bins over [-limit, limit] (values outside are counted
/// in the outermost bins).
std::vector<int> Histogram(const std::vector<double>& values, double limit, int bins);

/// The image rectangle with every corner found as a dot, one colour per view, the grid of
/// CornerCoverage over it and its empty cells shaded.
std::string CoverageSvg(const IntrinsicsCalibrationResult& result, const CoverageGrid& grid);

/// Three panels: the residual vectors magnified at their corners over the image, their
/// length against the distance from the principal point, and the histogram of their x and y
/// components with the normal density of the residual sigma.
std::string ResidualsSvg(const IntrinsicsCalibrationResult& result);

/// The names of the report's files, relative to the page (beside each other).
struct ReportFiles {
  std::string camera_yaml;
  std::string coverage_svg;
  std::string residuals_svg;
  std::string text_report;
};

/// The page: parameter table with sigmas and how they were computed, RMS, coverage, the
/// per-view table, and the two pictures (linked and shown).
std::string ReportHtml(const IntrinsicsCalibrationResult& result, const CoverageGrid& grid,
                       const ReportFiles& files);

}  // namespace h4::cam
