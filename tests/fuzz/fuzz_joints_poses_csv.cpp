// Fuzz target: the joints CSV, poses CSV, fk output and offline board poses readers (one
// input, every reader); what the poses reader accepts must write and read back.
#include "common/formats/board_poses_csv.h"
#include "common/formats/joints_csv.h"
#include "common/formats/poses_csv.h"
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
  return 0;
}
