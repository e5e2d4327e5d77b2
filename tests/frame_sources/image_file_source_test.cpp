// Tests for firmware/sources/image_file_source: directory listing, colour to grey,
// refusal of 16-bit images with a message naming the file.
#include "firmware/sources/image_file_source.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace h4::cam {
namespace {
namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(H4_BINARY_DIR) / "test_tmp" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(ImageFileSourceTest, DirectoryGivesItsImagesSortedByNameAsGrey) {
  const fs::path dir = FreshDir("image_source_dir");
  cv::imwrite((dir / "b.png").string(), cv::Mat(4, 6, CV_8UC3, cv::Scalar(0, 0, 255)));
  cv::imwrite((dir / "a.pgm").string(), cv::Mat(4, 6, CV_8UC1, cv::Scalar(77)));
  std::FILE* f = std::fopen((dir / "notes.txt").c_str(), "w");  // not an image: ignored
  std::fclose(f);
  ImageFileSource source({dir.string()});
  ASSERT_TRUE(source.Open()) << source.error();
  ASSERT_EQ(source.files().size(), 2u);
  auto first = source.Next(std::chrono::milliseconds(0));
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(fs::path(first->origin).filename(), "a.pgm");
  EXPECT_EQ(first->image.type(), CV_8UC1);
  EXPECT_EQ(first->image.at<uint8_t>(0, 0), 77);
  auto second = source.Next(std::chrono::milliseconds(0));
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->image.type(), CV_8UC1);
  EXPECT_NEAR(second->image.at<uint8_t>(1, 1), 76, 1);  // pure red: 0.299 * 255
  EXPECT_FALSE(source.Next(std::chrono::milliseconds(0)).has_value());
  EXPECT_TRUE(source.finished());
}

TEST(ImageFileSourceTest, SixteenBitImageIsRefusedNamingTheFile) {
  const fs::path dir = FreshDir("image_source_16bit");
  const std::string path = (dir / "deep.png").string();
  cv::imwrite(path, cv::Mat(4, 4, CV_16UC1, cv::Scalar(1000)));
  ImageFileSource source({path});
  ASSERT_TRUE(source.Open());
  EXPECT_FALSE(source.Next(std::chrono::milliseconds(0)).has_value());
  EXPECT_NE(source.error().find("deep.png"), std::string::npos);
  EXPECT_NE(source.error().find("16-bit"), std::string::npos);
}

// issue 27 point 16: a JPEG cut in half was decoded ("Premature end of JPEG file", the rest
// grey) and measured. It is refused naming the file; the whole file still reads.
TEST(ImageFileSourceTest, ATruncatedJpegIsRefusedNamingTheFile) {
  const fs::path dir = FreshDir("image_source_truncated_jpeg");
  cv::Mat pattern(64, 64, CV_8UC1);
  cv::randu(pattern, 0, 255);
  std::vector<uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", pattern, jpeg));
  const auto write = [&](const std::string& name, size_t size) {
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(jpeg.data()), static_cast<std::streamsize>(size));
    return path;
  };
  const std::string whole = write("whole.jpg", jpeg.size());
  const std::string half = write("half.jpg", jpeg.size() / 2);
  std::string why;
  EXPECT_FALSE(ImageFileSource::ReadGrey(whole, &why).empty()) << why;
  ImageFileSource source({half});
  ASSERT_TRUE(source.Open());
  EXPECT_FALSE(source.Next(std::chrono::milliseconds(0)).has_value());
  EXPECT_NE(source.error().find("half.jpg: truncated JPEG"), std::string::npos) << source.error();
  // Zero padding after the end marker is not a truncation; a file that is no JPEG is left
  // to its decoder.
  std::vector<uint8_t> padded = jpeg;
  padded.insert(padded.end(), 16, 0x00);
  EXPECT_FALSE(IsTruncatedJpeg(padded));
  EXPECT_TRUE(IsTruncatedJpeg({jpeg.begin(), jpeg.begin() + static_cast<long>(jpeg.size() - 1)}));
  EXPECT_FALSE(IsTruncatedJpeg({0x89, 'P', 'N', 'G'}));
}

TEST(ImageFileSourceTest, MissingPathFailsOpen) {
  ImageFileSource source({"/nonexistent/h4/images"});
  EXPECT_FALSE(source.Open());
  EXPECT_NE(source.error().find("/nonexistent/h4/images"), std::string::npos);
}

}  // namespace
}  // namespace h4::cam
