// Tests for firmware/sources/image_file_source: directory listing, colour to grey,
// refusal of 16-bit images with a message naming the file.
#include "firmware/sources/image_file_source.h"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <future>
#include <fstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>
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
  cv::imwrite((dir / "b.png").string(), cv::Mat(32, 40, CV_8UC3, cv::Scalar(0, 0, 255)));
  cv::imwrite((dir / "a.pgm").string(), cv::Mat(32, 40, CV_8UC1, cv::Scalar(77)));
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
  cv::imwrite(path, cv::Mat(32, 32, CV_16UC1, cv::Scalar(1000)));
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

// Issue 42 point 1: an image 4 px high or less segfaulted libapriltag (measure, preview,
// calibrate-intrinsics). Every format's header is read before decoding: under 32 px a side
// the file is refused naming it and its size; 32 x 32 is read.
TEST(ImageFileSourceTest, AnImageUnderTheSmallestSideIsRefusedFromItsHeader) {
  const fs::path dir = FreshDir("image_source_tiny");
  for (const char* name : {"tiny.png", "tiny.pgm", "tiny.bmp", "tiny.tif", "tiny.jpg"}) {
    const std::string path = (dir / name).string();
    ASSERT_TRUE(cv::imwrite(path, cv::Mat(3, 64, CV_8UC1, cv::Scalar(128)))) << name;
    std::string why;
    EXPECT_TRUE(ImageFileSource::ReadGrey(path, &why).empty()) << name;
    EXPECT_NE(why.find(path + ": image 64x3 px: expected 32..16384 px a side"), std::string::npos)
        << why;
    const std::string square = (dir / (std::string("square_") + name)).string();
    ASSERT_TRUE(cv::imwrite(square, cv::Mat(32, 32, CV_8UC1, cv::Scalar(128)))) << name;
    EXPECT_EQ(ImageFileSource::ReadGrey(square, &why).size(), cv::Size(32, 32)) << why;
  }
  // The fuzz corpus's tiny images (tests/fuzz/corpus/measure_image) are refused alike.
  const fs::path corpus = fs::path(H4_SOURCE_DIR) / "tests/fuzz/corpus/measure_image";
  for (const char* name : {"tiny_64x3.png", "tiny_3x64.png", "tiny_64x4.png", "tiny_1x1.png",
                           "tiny_64x3.pgm", "tiny_64x2.bmp"}) {
    std::string why;
    EXPECT_TRUE(ImageFileSource::ReadGrey((corpus / name).string(), &why).empty()) << name;
    EXPECT_NE(why.find("px: expected 32..16384 px a side"), std::string::npos) << why;
  }
}

// Issue 42 point 2: a 1 MB PNG of 32000 x 32000 px took 3.6 GB to decode. Its header is read
// first: refused naming the size, in far less time and memory than a decode (the header
// alone is given here, so a decode would fail differently: "cannot read the image").
TEST(ImageFileSourceTest, AnImageOverThePixelLimitIsRefusedBeforeDecoding) {
  const fs::path dir = FreshDir("image_source_huge");
  std::vector<uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(32, 32, CV_8UC1, cv::Scalar(9)), png));
  // IHDR's width and height (bytes 16..23, big-endian): 32000 x 32000. The CRC no longer
  // matches; the size check comes before anything looks at it.
  for (size_t at : {16u, 20u}) {
    png[at] = 0;
    png[at + 1] = 0;
    png[at + 2] = 0x7D;
    png[at + 3] = 0x00;
  }
  const std::string path = (dir / "huge.png").string();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  std::string why;
  EXPECT_TRUE(ImageFileSource::ReadGrey(path, &why).empty());
  EXPECT_NE(why.find(path + ": image 32000x32000 px: expected"), std::string::npos) << why;
  EXPECT_FALSE(ImageFileSource::HeaderSize(path, &why).has_value());
  EXPECT_NE(why.find("32000x32000 px"), std::string::npos) << why;
}

// Issue 42 point 3: a FIFO named as an image was waited on forever, /dev/zero read until
// memory ran out. A FIFO and a device (/dev/null here: /dev/zero would exhaust the memory
// of a regression instead of failing it) are refused at once as not regular files.
TEST(ImageFileSourceTest, AFifoOrADeviceIsRefusedWithoutWaiting) {
  const fs::path dir = FreshDir("image_source_fifo");
  const std::string fifo = (dir / "frame.png").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : {fifo, std::string("/dev/null")}) {
    std::future<std::string> why = std::async(std::launch::async, [path] {
      std::string reason;
      ImageFileSource::ReadGrey(path, &reason);
      return reason;
    });
    if (why.wait_for(std::chrono::seconds(5)) != std::future_status::ready) {
      const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (writer >= 0) ::close(writer);
      FAIL() << path << ": reading it as an image still blocks";
    }
    EXPECT_NE(why.get().find(path + ": cannot read the image: not a regular file"),
              std::string::npos);
  }
  // Named to the source (h4cam measure, capture): refused by name, not "no such file".
  ImageFileSource source({fifo});
  EXPECT_FALSE(source.Open());
  EXPECT_EQ(source.error(), fifo + ": not a regular file");
}

TEST(ImageFileSourceTest, MissingPathFailsOpen) {
  ImageFileSource source({"/nonexistent/h4/images"});
  EXPECT_FALSE(source.Open());
  EXPECT_NE(source.error().find("/nonexistent/h4/images"), std::string::npos);
}

}  // namespace
}  // namespace h4::cam
