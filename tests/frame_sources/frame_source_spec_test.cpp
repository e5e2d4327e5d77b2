// The frame source text of --source and `source:` (firmware/sources/frame_source_spec.h),
// and the source it names (firmware/sources/make_frame_source.h).
#include "firmware/sources/frame_source_spec.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "firmware/render/paper_scenes.h"
#include "firmware/sources/make_frame_source.h"

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

// Each kind takes its own part: the camera id, the folder, the board and the camera the
// renderer draws through.
TEST(MakeFrameSource, MakesTheKindTheSpecNamesFromItsPart) {
  std::string why;
  FrameSourceParts parts;
  parts.libcamera.camera_id = "cam9";
  EXPECT_EQ(MakeFrameSource(*ParseFrameSourceSpec("libcamera", &why), parts)->Describe(),
            "libcamera cam9");
  EXPECT_EQ(MakeFrameSource(*ParseFrameSourceSpec("dir:/data/frames", &why), parts)->Describe(),
            "files: /data/frames");

  const BoardSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  const FrameSourceSpec sim_spec = *ParseFrameSourceSpec("sim", &why);
  EXPECT_THROW(MakeFrameSource(sim_spec, parts), std::invalid_argument);
  parts.board = &board;
  parts.rendered_camera = &camera;
  const std::unique_ptr<FrameSource> sim = MakeFrameSource(sim_spec, parts);
  ASSERT_EQ(sim->Describe(), "sim");
  ASSERT_TRUE(sim->Open());
  const std::optional<Frame> frame = sim->Next(std::chrono::milliseconds(100));
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->image.cols, camera.width);
  EXPECT_EQ(frame->image.rows, camera.height);
}

}  // namespace
}  // namespace h4::cam
