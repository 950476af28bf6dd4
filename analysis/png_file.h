// PNG output of the analysis module's pictures (OpenCV adapter: the only header that names cv::Mat for writing).
#pragma once

#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

namespace waam::analysis::internal {

// The PNG bytes of an 8-bit `image` (1, 3 or 4 channels), with OpenCV's imwrite `params` (e.g. compression).
// Encoding a picture the code drew cannot fail on bad input: a failure is an InternalError (WAAM_DEMAND).
std::vector<unsigned char> EncodePng(const cv::Mat& image, const std::vector<int>& params = {});

// Writes `image` as a PNG to `path` atomically. Throws OutputError naming `path` and the reason if it cannot be written.
void WritePngAtomic(const cv::Mat& image, const std::filesystem::path& path, const std::vector<int>& params = {});

}  // namespace waam::analysis::internal
