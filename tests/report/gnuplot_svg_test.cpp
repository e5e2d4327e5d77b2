// gnuplot as a subprocess (host/report/gnuplot_svg.h): the SVG comes back, gnuplot's own
// message comes back on failure, and a temporary folder whose path holds a quote or a space
// does not break it (it once ran through a shell string, `gnuplot '<path>'`).
#include "host/report/gnuplot_svg.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

namespace h4::host {
namespace {

namespace fs = std::filesystem;

constexpr const char* kLine = "plot '-' with lines\n0 0\n1 1\ne\n";

TEST(GnuplotSvg, ReturnsTheSvgElement) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const std::string svg = RenderSvg(kLine, 320, 200);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u) << svg.substr(0, 200);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("320"), std::string::npos) << "the size given is the size drawn";
}

TEST(GnuplotSvg, AScriptErrorCarriesGnuplotsMessage) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  try {
    RenderSvg("plot no_such_function(x)\n");
    FAIL() << "a broken script drew a figure";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_function"), std::string::npos) << e.what();
  }
}

TEST(GnuplotSvg, ATemporaryFolderWithAQuoteAndASpaceInItsPathStillWorks) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot missing: run scripts/setup";
  const fs::path odd =
      fs::path(H4_BINARY_DIR) / "test_tmp" / fmt::format("it's a tmp {}", ::getpid());
  fs::create_directories(odd);
  const char* previous = std::getenv("TMPDIR");
  const std::string saved = previous ? previous : "";
  setenv("TMPDIR", odd.c_str(), 1);
  std::string svg;
  EXPECT_NO_THROW(svg = RenderSvg(kLine));
  if (previous) {
    setenv("TMPDIR", saved.c_str(), 1);
  } else {
    unsetenv("TMPDIR");
  }
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_TRUE(fs::is_empty(odd)) << "the temporary folder is removed";
  fs::remove_all(odd);
}

}  // namespace
}  // namespace h4::host
