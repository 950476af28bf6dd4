// analysis/png_file: libpng round trips keep every pixel (grey, BGR, BGRA), and bad bytes or paths are refused.
#include "analysis/png_file.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis::internal {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// An image of `type` whose every byte differs from its neighbours': (7 r + 13 c + 31 channel) mod 256.
cv::Mat KnownPixels(int rows, int cols, int type) {
  cv::Mat image(rows, cols, type);
  const int channels = image.channels();
  for (int r = 0; r < rows; ++r) {
    unsigned char* row = image.ptr<unsigned char>(r);
    for (int c = 0; c < cols * channels; ++c) {
      row[c] = static_cast<unsigned char>((7 * r + 13 * c + 31 * (c % channels)) % 256);
    }
  }
  return image;
}

// The number of bytes at which `a` and `b` differ (sizes and types must match).
int DifferentBytes(const cv::Mat& a, const cv::Mat& b) {
  EXPECT_EQ(a.size(), b.size());
  EXPECT_EQ(a.type(), b.type());
  if (a.size() != b.size() || a.type() != b.type()) return -1;
  int differ = 0;
  for (int r = 0; r < a.rows; ++r) {
    for (int c = 0; c < a.cols * a.channels(); ++c) differ += a.ptr<unsigned char>(r)[c] != b.ptr<unsigned char>(r)[c];
  }
  return differ;
}

TEST(PngFile, GreyBgrAndBgraRoundTripEveryPixel) {
  const fs::path dir = fs::path(::waam_test_env::TempDir()) / "png_file_round_trip";
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4}) {
    const cv::Mat image = KnownPixels(37, 53, type);
    const fs::path path = dir / ("image_" + std::to_string(CV_MAT_CN(type)) + ".png");
    WritePngAtomic(image, path);
    EXPECT_EQ(DifferentBytes(ReadPng(path, image.channels()), image), 0) << path;
  }
}

TEST(PngFile, AnImageWithARowStrideWiderThanItsPixels) {
  const cv::Mat big = KnownPixels(40, 60, CV_8UC3);
  const cv::Mat roi = big(cv::Rect(5, 3, 21, 17));
  ASSERT_FALSE(roi.isContinuous());
  const std::vector<unsigned char> bytes = EncodePng(roi);
  const cv::Mat back = DecodePng(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), 3, "roi");
  EXPECT_EQ(DifferentBytes(back, roi.clone()), 0);
}

TEST(PngFile, GreyReadAsBgrRepeatsTheGreyInEachChannel) {
  const cv::Mat grey = KnownPixels(9, 11, CV_8UC1);
  const std::vector<unsigned char> bytes = EncodePng(grey);
  const cv::Mat bgr = DecodePng(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), 3, "g");
  ASSERT_EQ(bgr.type(), CV_8UC3);
  for (int r = 0; r < grey.rows; ++r) {
    for (int c = 0; c < grey.cols; ++c) {
      const unsigned char g = grey.at<unsigned char>(r, c);
      EXPECT_EQ(bgr.at<cv::Vec3b>(r, c), cv::Vec3b(g, g, g)) << r << ", " << c;
    }
  }
}

TEST(PngFile, NotAPngOrTruncatedIsAnInputErrorNamingTheFile) {
  const std::vector<unsigned char> bytes = EncodePng(KnownPixels(30, 30, CV_8UC3));
  const std::string whole(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  for (const std::string& bad : {std::string("GIF89a not a png"), whole.substr(0, whole.size() / 2), std::string()}) {
    try {
      DecodePng(bad, 3, "shot.png");
      ADD_FAILURE() << "accepted " << bad.size() << " bytes";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("shot.png: ")) << e.what();
    }
  }
}

TEST(PngFile, AChunkLongerThanTheFileIsRefusedBeforeItIsAllocated) {
  // A real picture's header followed by a text chunk that declares 1 GiB (found by fuzz/png_fuzzer.cc: libpng
  // allocated and cleared the whole chunk before finding the file short).
  const std::vector<unsigned char> bytes = EncodePng(KnownPixels(30, 30, CV_8UC3));
  std::string png(reinterpret_cast<const char*>(bytes.data()), 8 + 25);  // signature and IHDR
  png += std::string("\x40\x00\x00\x39", 4) + "tEXtSoftware";
  try {
    DecodePng(png, 3, "shot.png");
    ADD_FAILURE() << "accepted a chunk longer than the file";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("shot.png: corrupt PNG (chunk 'tEXt' at byte 33 declares 1073741881 bytes"))
        << e.what();
  }
}

TEST(PngFile, AWriteUnderARegularFileIsAnOutputErrorNamingThePathAndReason) {
  const fs::path dir = fs::path(::waam_test_env::TempDir()) / "png_file_under_file";
  fs::create_directories(dir);
  std::ofstream(dir / "a_file") << "x";
  const fs::path path = dir / "a_file" / "picture.png";
  try {
    WritePngAtomic(KnownPixels(4, 4, CV_8UC1), path);
    ADD_FAILURE() << "wrote " << path;
  } catch (const OutputError& e) {
    // The parent that is a file is the path the write fails on.
    EXPECT_THAT(e.what(), HasSubstr("cannot write " + (dir / "a_file").string() + ": ")) << e.what();
  }
}

}  // namespace
}  // namespace waam::analysis::internal
