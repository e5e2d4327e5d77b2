// `h4cam measure --board B.yaml --camera camera.yaml [--frames 10] IMAGES... --out
// poses.csv`: offline board poses
// (common/formats/README.md#offline-board-poses-csv-h4cam-measure---out) from image files, each
// group of N consecutive images averaged into one measurement, one row per group (empty pose fields
// when the group gives no usable pose). Progress on stderr.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace h4::cam {

struct MeasureArgs {
  std::string board_path;
  std::string camera_path;
  std::vector<std::string> images;  ///< files and/or directories, in order
  int group = 10;                   ///< images averaged per measurement
  double max_spread_px = 0.5;       ///< motion threshold, the camera service's (service_config.h)
  std::string out_path;
  /// Board-corner CSV (common/formats/README.md#board-corners-csv) of the poses in
  /// `out_path`: pose_id is the row's number there, from 0. Empty: not written.
  std::string corners_out_path;
};

void DeclareMeasureCommand(CLI::App* command);

/// Runs the measurement; returns the number of rows with a pose. Throws (std::runtime_error
/// or h4::FormatError) naming the file at fault: an unreadable or 16-bit image, an image
/// of another size than the camera file says, an unwritable output.
int RunMeasure(const MeasureArgs& args, std::ostream& progress);

}  // namespace h4::cam
