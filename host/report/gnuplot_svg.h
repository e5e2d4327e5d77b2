// Figures for the HTML report, drawn by gnuplot (Debian gnuplot-nox) as SVG that the report
// inlines: a well-kept plotting program, no JavaScript, nothing fetched when the page opens.
// gnuplot runs as a subprocess (an argument vector, no shell) with the script on a temporary
// file; its stdout is the SVG.
#pragma once

#include <string>

namespace h4::host {

/// Whether a gnuplot executable is on PATH.
bool GnuplotAvailable();

/// Runs `script` (gnuplot commands, inline data blocks allowed; no `set terminal` or
/// `set output`: the size is given here) and returns the <svg> element, without the XML
/// prolog. Throws std::runtime_error with gnuplot's own message when it is missing or fails.
std::string RenderSvg(const std::string& script, int width_px = 720, int height_px = 400);

}  // namespace h4::host
