// `h4cam calibrate-intrinsics --board B.yaml IMAGES... --out camera.yaml
// [--model radtan|rational|equidistant]`: finds the board in each image (chessboard or
// AprilTag grid), calibrates the camera (intrinsics_calibration.h), prints each parameter
// with its 1-sigma and per-view errors with outliers named, and writes the camera YAML with
// its distortion_model (common/formats/README.md) and, beside it and named after it, the
// report (intrinsics_report.h): camera.yaml -> camera-report.html (parameters, coverage,
// residuals, views) with camera-coverage.svg, camera-residuals.svg and camera-report.txt
// (the console report). Refuses (non-zero exit) view sets that cannot determine the focal
// length.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "firmware/calibration/intrinsics_calibration.h"

namespace CLI {
class App;
}

namespace h4::cam {

struct CalibrateIntrinsicsArgs {
  std::string board_path;           ///< board YAML
  std::vector<std::string> images;  ///< image files, all of one size
  std::string out_path;             ///< camera YAML written here
  IntrinsicsCalibrationOptions options;
};

void DeclareCalibrateIntrinsicsCommand(CLI::App* command);

/// Runs the calibration, reporting to `out`; returns the result (the YAML is written only
/// when it is ok()). Throws std::runtime_error (or h4::FormatError) naming the file when an
/// input cannot be read, images differ in size, or the calibration fails.
IntrinsicsCalibrationResult RunCalibrateIntrinsics(const CalibrateIntrinsicsArgs& args,
                                                   std::ostream& out);

}  // namespace h4::cam
