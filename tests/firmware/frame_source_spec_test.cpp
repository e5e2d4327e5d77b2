// The frame source text of --source and `source:` (firmware/sources/frame_source_spec.h).
#include "firmware/sources/frame_source_spec.h"

#include <gtest/gtest.h>

namespace h4::cam {
namespace {

TEST(FrameSourceSpec, NamesTheCameraTheRendererOrImageFiles) {
  std::string why;
  EXPECT_EQ(ParseFrameSourceSpec("libcamera", &why)->kind, FrameSourceSpec::Kind::kLibcamera);
  EXPECT_EQ(ParseFrameSourceSpec("sim", &why)->kind, FrameSourceSpec::Kind::kSim);
  const std::optional<FrameSourceSpec> files = ParseFrameSourceSpec("dir:/data/frames", &why);
  ASSERT_TRUE(files.has_value());
  EXPECT_EQ(files->kind, FrameSourceSpec::Kind::kImageFiles);
  EXPECT_EQ(files->path, "/data/frames");
}

TEST(FrameSourceSpec, AnythingElseSaysWhatWasExpected) {
  std::string why;
  EXPECT_FALSE(ParseFrameSourceSpec("dir:", &why).has_value());
  EXPECT_EQ(why, "source 'dir:' names no folder");
  for (const char* text : {"", "Sim", "libcamera ", "/data/frames", "file:/x"}) {
    why.clear();
    EXPECT_FALSE(ParseFrameSourceSpec(text, &why).has_value()) << text;
    EXPECT_EQ(why, "source '" + std::string(text) + "': expected libcamera, sim or dir:PATH");
  }
}

}  // namespace
}  // namespace h4::cam
