// The report's figures, as inline SVG drawn by gnuplot: joint residuals per evaluated pose
// (held out, or in-sample) and joint (before / after), residual histograms, the
// straightness runs' distances to their fitted lines, and the square path commanded vs
// reached (simulated) or measured.
#pragma once

#include <string>

#include "host/validation/validation.h"

namespace h4::host {

std::string ResidualsFigure(const ValidationReport& report);
std::string HistogramFigure(const ValidationReport& report);
/// Precondition: the models have straightness runs.
std::string StraightnessFigure(const ValidationReport& report);
/// Precondition: some model has a square run.
std::string SquareFigure(const ValidationReport& report);
/// Precondition: the report has measured square runs of `plan`.
std::string MeasuredSquareFigure(const SquarePlan& plan, const ValidationReport& report);
/// The accuracy map of one model: a panel per Z level (columns) and theta (rows), each
/// grid pose a square coloured by its predicted 1-sigma position error, one colour scale.
std::string AccuracyMapFigure(const AccuracyMap& map, const std::string& label);
/// The corner residual map over the image: each cell coloured by its residual RMS, an
/// arrow from its centre along its mean residual (measured - predicted), scaled up so that
/// the largest spans most of a cell (the scale in the title). Image axes, v down.
std::string CornerResidualFigure(const CornerResidualMap& map);

}  // namespace h4::host
