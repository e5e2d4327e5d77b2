// A bare board name on a command line names an installed board (common/cli/board_lookup.h):
// the README's walkthrough writes `--board aprilgrid_6x6_30mm.yaml` from any folder.
#include "common/cli/board_lookup.h"

#include <fstream>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "tests/support/format_error_helpers.h"

namespace h4::cli {
namespace {

namespace fs = std::filesystem;

class BoardLookup : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::path(TempPath("boards"));
    fs::create_directories(folder_);
    std::ofstream(folder_ / "grid.yaml") << "target_type: aprilgrid\n";
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

TEST_F(BoardLookup, ABareNameIsFoundInTheInstalledFolderWithOrWithoutYaml) {
  const std::string expected = (folder_ / "grid.yaml").string();
  EXPECT_EQ(ResolveBoardPath("grid.yaml", {"/nonexistent", folder_}), expected);
  EXPECT_EQ(ResolveBoardPath("grid", {folder_}), expected);
  EXPECT_EQ(ResolveBoardPath("other.yaml", {folder_}), "");
}

TEST_F(BoardLookup, APathIsTakenAsItIs) {
  EXPECT_EQ(ResolveBoardPath("./grid.yaml", {folder_}), "./grid.yaml");
}

TEST_F(BoardLookup, TheBoardOptionTakesTheInstalledBoardAndNamesWhereItLooked) {
  CLI::App app;
  std::string board;
  app.add_option("--board", board)->transform(ExistingBoardFile({folder_}));
  app.parse(std::vector<std::string>{"grid.yaml", "--board"});  // CLI11 parses in reverse
  EXPECT_EQ(board, (folder_ / "grid.yaml").string());
  try {
    app.parse(std::vector<std::string>{"missing.yaml", "--board"});
    FAIL() << "a board found nowhere was accepted";
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find(folder_.string()), std::string::npos) << e.what();
  }
}

TEST_F(BoardLookup, TheCameraOptionTakesAnInstalledCameraFileAndKeepsTheCamchainBlock) {
  std::ofstream(folder_ / "camchain.yaml") << "cam0: {}\n";
  CLI::App app;
  std::string camera;
  app.add_option("--camera", camera)->transform(ExistingCameraFile({folder_}));
  app.parse(std::vector<std::string>{"camchain.yaml#cam1", "--camera"});
  EXPECT_EQ(camera, (folder_ / "camchain.yaml").string() + "#cam1");
  app.parse(std::vector<std::string>{"camchain", "--camera"});
  EXPECT_EQ(camera, (folder_ / "camchain.yaml").string());
  try {
    app.parse(std::vector<std::string>{"missing.yaml#cam0", "--camera"});
    FAIL() << "a camera file found nowhere was accepted";
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("File does not exist: missing.yaml ("), std::string::npos)
        << e.what();
  }
}

TEST(BoardLookupFolders, ThePackagedFolderThenTheSourceTreesComeLast) {
  const std::vector<fs::path> folders = InstalledBoardFolders();
  ASSERT_GE(folders.size(), 2u);
  EXPECT_EQ(folders[folders.size() - 2], fs::path("/usr/share/h4cam/boards"));
  EXPECT_EQ(folders.back(), fs::path("boards"));
}

}  // namespace
}  // namespace h4::cli
