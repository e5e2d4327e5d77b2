// Fuzz target: the paired dataset CSV reader; what it accepts must write and read back
// to the same rows.
#include "host/formats/dataset_csv.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const auto rows = fuzz::ParseOrRefuse(
      fuzz::Text(data, size), [](const std::string& t) { return ParseDatasetCsv(t, "fuzz.csv"); });
  if (!rows) return 0;
  const std::vector<DatasetRow> back = ParseDatasetCsv(FormatDatasetCsv(*rows), "written.csv");
  fuzz::Require(back.size() == rows->size(), "dataset round trip keeps every row");
  for (size_t i = 0; i < back.size(); ++i) {
    fuzz::Require(back[i].pose_id == (*rows)[i].pose_id && back[i].q == (*rows)[i].q &&
                      back[i].sigma_t == (*rows)[i].sigma_t,
                  "dataset round trip keeps the values");
  }
  return 0;
}
