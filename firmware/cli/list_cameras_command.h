// `h4cam list-cameras`: the cameras libcamera sees, one per line ("<id>  <model>").
// Without a camera it prints "no cameras found" and exits 0: an empty list is an answer,
// not a failure (scripts test the output, or open the camera and get a clear error).
#pragma once

#include <iosfwd>

namespace CLI {
class App;
}

namespace h4::cam {

void DeclareListCamerasCommand(CLI::App* command);

/// Writes the listing to `out`; returns the exit code (0, also with no camera). Throws
/// std::runtime_error when the camera stack cannot start.
int RunListCameras(std::ostream& out);

}  // namespace h4::cam
