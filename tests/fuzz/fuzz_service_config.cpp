// Fuzz target: the camera service configuration reader (h4cam run --config); what it
// accepts must pass ServiceConfig::IsValid (the limits the service relies on).
#include "firmware/service/service_config.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const auto config = fuzz::ParseOrRefuse(fuzz::Text(data, size), [](const std::string& t) {
    return cam::ParseServiceConfig(t, "h4cam.yaml");
  });
  if (!config) return 0;
  std::string why;
  fuzz::Require(config->IsValid(&why), "an accepted configuration is valid");
  return 0;
}
