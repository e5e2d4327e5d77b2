// Fuzz target: the identification result JSON reader; what it accepts must write and read
// back.
#include "host/formats/identification_result.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const auto result = fuzz::ParseOrRefuse(fuzz::Text(data, size), [](const std::string& t) {
    return ParseIdentificationResult(t, "r.json");
  });
  if (!result) return 0;
  const IdentificationResult back =
      ParseIdentificationResult(FormatIdentificationResult(*result), "written.json");
  fuzz::Require(back.parameters.size() == result->parameters.size(),
                "result round trip keeps every parameter");
  return 0;
}
