// The report's tables as HTML fragments: parameters, identifiability, and the analogues of
// the paper's Tables 2, 3 and 4, the positioning error, the square path and the 4-DoF check,
// each with the paper's numbers beside ours on the paper scenario.
#pragma once

#include <string>

#include "common/text/markup_escape.h"
#include "host/validation/validation.h"

namespace h4::host {

std::string SummaryTable(const ValidationInputs& in, const ValidationReport& report);
std::string ParameterTables(const ValidationInputs& in);
std::string IdentifiabilityTable(const ValidationInputs& in);
std::string Table2(const ValidationInputs& in, const ValidationReport& report);
std::string Table3(const ValidationReport& report);
std::string PositioningTable(const ValidationReport& report);
/// Per identified model with an accuracy map: per Z level and theta, the median and largest
/// predicted position sigma, and how many grid poses were left out. Empty when none has one.
std::string AccuracyMapTable(const ValidationReport& report);
std::string Table4(const ValidationReport& report);
std::string SquareTable(const ValidationInputs& in, const ValidationReport& report);
std::string FourDofTable(const ValidationReport& report);

}  // namespace h4::host
