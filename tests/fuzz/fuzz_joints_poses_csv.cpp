// Fuzz target: the joints CSV, poses CSV, fk output, offline board poses and board corner
// readers (one input, every reader); what the poses and corner readers accept must write
// and read back.
#include "common/formats/board_poses_csv.h"
#include "common/formats/corners_csv.h"
#include "host/formats/joints_csv.h"
#include "host/formats/poses_csv.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const std::string text = fuzz::Text(data, size);
  fuzz::ParseOrRefuse(text, [](const std::string& t) { return ParseJointsCsv(t, "j.csv"); });
  fuzz::ParseOrRefuse(text, [](const std::string& t) { return ParseFkCsv(t, "fk.csv"); });
  fuzz::ParseOrRefuse(text, [](const std::string& t) { return ParseBoardPosesCsv(t, "b.csv"); });
  const auto poses =
      fuzz::ParseOrRefuse(text, [](const std::string& t) { return ParsePosesCsv(t, "p.csv"); });
  if (poses) {
    const auto back = ParsePosesCsv(FormatPosesCsv(*poses), "written.csv");
    fuzz::Require(back.size() == poses->size(), "poses round trip keeps every row");
  }
  const auto corners =
      fuzz::ParseOrRefuse(text, [](const std::string& t) { return ParseCornersCsv(t, "c.csv"); });
  if (corners) {
    std::string written = CornersCsvHeader(true) + "\n";
    for (const CornerObservation& c : *corners) written += CornersCsvLine(c, true) + "\n";
    fuzz::RequireRoundTrip(
        *corners, ParseCornersCsv(written, "written.csv"),
        [](const CornerObservation& b, const CornerObservation& a) {
          return b.u == a.u && b.v == a.v && b.sigma_px == a.sigma_px;
        },
        "corners round trip");
  }
  return 0;
}
