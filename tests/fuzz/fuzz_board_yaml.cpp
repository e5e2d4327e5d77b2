// Fuzz target: the board YAML reader, then the board model built from what it accepts
// (where a huge count would allocate); accepted boards must write and read back.
#include "common/board/board_model.h"
#include "common/formats/board_yaml.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const auto board = fuzz::ParseOrRefuse(
      fuzz::Text(data, size), [](const std::string& t) { return ParseBoardYaml(t, "b.yaml"); });
  if (!board) return 0;
  const BoardModel model(*board);
  (void)model;
  const BoardSpec back = ParseBoardYaml(FormatBoardYaml(*board), "written.yaml");
  fuzz::Require(back.index() == board->index(), "board round trip keeps the type");
  return 0;
}
