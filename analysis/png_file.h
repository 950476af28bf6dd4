// PNG files of the analysis module's pictures, encoded and decoded by libpng's simplified API (cv::Mat in and out).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace waam::analysis::internal {

// The PNG bytes of an 8-bit `image` with 1 (grey), 3 (BGR, OpenCV's order) or 4 (BGRA) channels; the file stores
// the same pixel values (grey, RGB or RGBA, 8 bits per channel). Encoding a picture the code drew cannot fail on bad
// input: an empty image, another depth or channel count, or a libpng failure is an InternalError (WAAM_DEMAND).
std::vector<unsigned char> EncodePng(const cv::Mat& image);

// Writes `image` (as EncodePng) as a PNG to `path` atomically. Throws OutputError naming `path` and the reason if it
// cannot be written (disk full, no permission, a parent that is a file).
void WritePngAtomic(const cv::Mat& image, const std::filesystem::path& path);

// Decodes the PNG `bytes` into an 8-bit image with `channels` = 1 (grey), 3 (BGR) or 4 (BGRA) channels, whatever the
// file's colour type and bit depth (libpng converts; 16-bit samples are rounded to 8 bits, an alpha channel that the
// output lacks is composited onto black). Throws InputError naming `name` and libpng's reason if the bytes are not a
// PNG, are truncated or corrupt, or hold more than kMaxPngPixels pixels.
cv::Mat DecodePng(std::string_view bytes, int channels, const std::string& name);

// Reads the PNG file at `path` as DecodePng. Throws InputError naming `path` if it cannot be read or decoded.
cv::Mat ReadPng(const std::filesystem::path& path, int channels);

// The largest picture DecodePng accepts (width x height), so that a header cannot make it allocate gigabytes.
inline constexpr long long kMaxPngPixels = 64LL * 1024 * 1024;

}  // namespace waam::analysis::internal
