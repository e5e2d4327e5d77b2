// Fuzz target: an image file through the measure path of `h4cam measure`. The bytes are
// read as ImageFileSource reads a file (ImageFileSource::DecodeGrey: the header's size checked
// against the image size limits, then cv::imdecode with IMREAD_UNCHANGED, 8-bit only, 1, 3
// or 4 channels), then measured with the demo's AprilGrid and with a 4 x 3 checkerboard:
// detection and pose on a camera of the image's size.
// Images larger than kMaxFuzzPixels are not measured (detection time grows with the
// area; the fuzzer's worth is in odd contents and shapes, not in size).
#include "firmware/pose/measure_pipeline.h"
#include "firmware/sources/image_file_source.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

constexpr int kMaxFuzzPixels = 160 * 120;

h4::CameraIntrinsics CameraOfSize(int width, int height) {
  const double f_px = 1.2 * std::max(width, height);
  return h4::CameraIntrinsics::Pinhole(width, height, f_px, f_px, 0.5 * (width - 1),
                                       0.5 * (height - 1));
}

// boards/aprilgrid_6x6_30mm.yaml, the demo's board.
h4::BoardSpec DemoAprilGrid() {
  h4::AprilGridSpec board;
  board.layout = h4::AprilGridLayout::kH4Legacy;
  return board;
}

h4::BoardSpec SmallCheckerboard() {
  h4::CheckerboardSpec board;
  board.cols = 4;
  board.rows = 3;
  return board;
}

void MeasureWith(const h4::BoardSpec& board, const cv::Mat& grey) {
  using namespace h4;
  cam::PipelineOptions options;
  options.frames = 1;
  const cam::MeasurePipeline pipeline(board, CameraOfSize(grey.cols, grey.rows), options);
  fuzz::Require(pipeline.ok(), "the pipeline takes a valid board and camera");
  const cam::Measurement m = pipeline.MeasureImage(grey, 1);
  if (m.ok()) {
    fuzz::Require(m.X_CT.translation().allFinite() && std::isfinite(m.rms_px) &&
                      std::isfinite(m.sigma_t) && std::isfinite(m.sigma_r),
                  "a measured pose is finite");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  std::string why;
  const cv::Mat grey = cam::ImageFileSource::DecodeGrey(
      std::string(reinterpret_cast<const char*>(data), size), "image", &why);
  if (grey.empty()) {
    fuzz::Require(!why.empty(), "a refused image says why");
    return 0;
  }
  fuzz::Require(ImageSizeProblem(grey.cols, grey.rows).empty(),
                "an accepted image is within the size limits");
  if (int64_t{grey.cols} * grey.rows > kMaxFuzzPixels) return 0;
  MeasureWith(DemoAprilGrid(), grey);
  MeasureWith(SmallCheckerboard(), grey);
  return 0;
}
