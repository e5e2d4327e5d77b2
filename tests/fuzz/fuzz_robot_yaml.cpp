// Fuzz target: the robot description YAML reader; what it accepts must write and read
// back.
#include "host/formats/robot_yaml.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const auto robot = fuzz::ParseOrRefuse(
      fuzz::Text(data, size), [](const std::string& t) { return ParseRobotYaml(t, "r.yaml"); });
  if (!robot) return 0;
  const RobotDescription back = ParseRobotYaml(FormatRobotYaml(*robot), "written.yaml");
  fuzz::Require(back.model12.arm == robot->model12.arm &&
                    back.model31.has_value() == robot->model31.has_value(),
                "robot.yaml round trip keeps the values");
  return 0;
}
