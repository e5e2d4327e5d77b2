// The report's figures, as gnuplot scripts that the page draws as inline SVG (RenderSvg):
// joint residuals per evaluated pose (held out, or in-sample) and joint (before / after),
// residual histograms, the straightness runs' distances to their fitted lines, the square
// path commanded vs reached (simulated) or measured, the accuracy map, the corner
// residual map and the board's coverage of the image. The scripts are returned, not drawn, so that
// tests can read what a figure shows (its ranges, series and labels) without parsing SVG.
#pragma once

#include <string>
#include <vector>

#include "host/validation/validation.h"

namespace h4::host {

/// A figure before drawing: gnuplot commands with inline data blocks, and its size.
struct GnuplotPlot {
  std::string script;
  int width_px = 720;
  int height_px = 400;
};

/// The plot as an <svg> element (gnuplot_svg.h); throws as RenderSvg does.
std::string DrawPlot(const GnuplotPlot& plot);

GnuplotPlot ResidualsPlot(const ValidationReport& report);
GnuplotPlot HistogramPlot(const ValidationReport& report);
/// Precondition: the models have straightness runs.
GnuplotPlot StraightnessPlot(const ValidationReport& report);
/// Precondition: some model has a square run.
GnuplotPlot SquarePlot(const ValidationReport& report);
/// Precondition: the report has measured square runs of `plan`.
GnuplotPlot MeasuredSquarePlot(const SquarePlan& plan, const ValidationReport& report);
/// The accuracy map of one model: a panel per Z level (columns) and theta (rows), each
/// grid pose a square coloured by its predicted 1-sigma position error, one colour scale;
/// over it the dataset's calibration poses and held-out poses (in the model's base frame,
/// ModelValidation), each in the panel of its nearest Z level and theta. No held-out series
/// when `held_out_poses` is empty (every pose in the fit).
GnuplotPlot AccuracyMapPlot(const AccuracyMap& map, const std::string& label,
                            const std::vector<EePose>& calibration_poses,
                            const std::vector<EePose>& held_out_poses);
/// The corner residual map over the image: each cell coloured by its residual RMS, an
/// arrow from its centre along its mean residual (measured - predicted), scaled up so that
/// the largest spans most of a cell (the scale in the title). Image axes, v down.
GnuplotPlot CornerResidualPlot(const CornerResidualMap& map);
/// The board's coverage of the image over the campaign: each row's board outline (the
/// rectangle around its corners) and centre projected from its measured X_CT through
/// `camera`, over the image rectangle (v down); the rows of `held_out_ids` apart.
GnuplotPlot BoardCoveragePlot(const std::vector<DatasetRow>& rows,
                              const std::vector<int64_t>& held_out_ids, const BoardModel& board,
                              const CameraIntrinsics& camera);

}  // namespace h4::host
