// `h4cam capture` and `h4cam preview`: what the camera sees, for aiming, focusing and
// collecting the images of `h4cam calibrate-intrinsics`, on any frame source (libcamera,
// the renderer `sim`, image files `dir:PATH`). Each frame is checked (frame_check.h) and
// one line of figures printed on stdout:
//   h4cam capture --source libcamera --board B.yaml --camera C.yaml --count 20 --out DIR
//       [--draw] [--interval 2]     saves DIR/frame_NNNN.png (and overlay_NNNN.png),
//       numbered on after the highest NNNN already in DIR (a capture never overwrites one)
//   h4cam capture --source sim ...  without --sim-pose, frame N shows the board at pose N
//       of a tilted sequence over the whole image (sim_capture_poses.h): the intrinsics
//       step rehearsed
//   h4cam preview --source libcamera --board B.yaml --camera C.yaml [--draw --out DIR]
//       until Ctrl-C (or --count); --draw keeps DIR/preview.png, the last frame with its
//       detection drawn, replaced atomically so an image viewer can reload it
// The camera file may hold nominal intrinsics (the lens's focal length, centre of the
// sensor) before the camera is calibrated: detection needs them only roughly; the
// reprojection RMS is then only indicative. Exit 0 when some frame showed the board, 3
// when none did, 130 when interrupted before any frame.
#pragma once

#include <atomic>
#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace h4::cam {

struct CaptureArgs {
  std::string source = "libcamera";  ///< libcamera | sim | dir:PATH
  std::string board_path;
  std::string camera_path;
  int count = 10;              ///< frames to check (and save); 0: until interrupted (preview)
  std::string out_dir;         ///< capture: frames (and overlays); preview: preview.png
  bool draw = false;           ///< also write the frame with its detection drawn
  double interval_s = 0;       ///< live sources: at least this long between frames taken, s
  std::string camera_id;       ///< libcamera camera id ("" = the first)
  double exposure_us = 0;      ///< libcamera: fixed exposure time, us (0 = automatic)
  double analogue_gain = 1.0;  ///< libcamera: with a fixed exposure
  /// sim: X_CT as x,y,z,qw,qx,qy,qz (m); empty: capture's pose sequence
  /// (sim_capture_poses.h), preview's board centred 0.5 m in front.
  std::vector<double> sim_pose;
  std::string sim_preset = "processed";  ///< sim: clean | processed (render_options.h)
  /// sim: scale of the light (1 = the preset's exposure; above ~1.2 the white clips).
  double sim_exposure = 1.0;
};

struct CaptureSummary {
  int frames = 0;      ///< frames checked
  int with_board = 0;  ///< of which the board was found (ok or partial)
};

/// The number of the next frame to save in a folder holding `file_names`: one after the
/// highest NNNN of frame_NNNN.png or overlay_NNNN.png, 0 when there is none.
int FirstFreeFrameNumber(const std::vector<std::string>& file_names);

/// Checks (and, with `save_frames`, saves) frames until args.count or `stop`; prints one
/// line per frame on `out`. Throws std::invalid_argument naming the option at fault, or
/// std::runtime_error naming the source or file that failed.
CaptureSummary RunCapture(const CaptureArgs& args, bool save_frames, std::ostream& out,
                          const std::atomic<bool>& stop);

void DeclareCaptureCommand(CLI::App* command);
void DeclarePreviewCommand(CLI::App* command);

}  // namespace h4::cam
