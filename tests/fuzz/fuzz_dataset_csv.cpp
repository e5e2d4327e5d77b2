// Fuzz target: the paired dataset CSV reader; what it accepts must write and read back
// to the same rows.
#include "host/formats/dataset_csv.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const auto rows = fuzz::ParseOrRefuse(
      fuzz::Text(data, size), [](const std::string& t) { return ParseDatasetCsv(t, "fuzz.csv"); });
  if (!rows) return 0;
  fuzz::RequireRoundTrip(
      *rows, ParseDatasetCsv(FormatDatasetCsv(*rows), "written.csv"),
      [](const DatasetRow& b, const DatasetRow& a) {
        return b.pose_id == a.pose_id && b.q == a.q && b.sigma_t == a.sigma_t;
      },
      "dataset round trip");
  return 0;
}
