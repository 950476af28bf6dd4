// PNG output: encoded in memory by OpenCV (which picks its encoder from the extension, so never from a temporary
// file name), written atomically by models/core/files.h.
#include "analysis/png_file.h"

#include <string_view>

#include <opencv2/imgcodecs.hpp>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis::internal {

std::vector<unsigned char> EncodePng(const cv::Mat& image, const std::vector<int>& params) {
  std::vector<unsigned char> bytes;
  const bool encoded = cv::imencode(".png", image, bytes, params);
  WAAM_DEMAND(encoded);
  return bytes;
}

void WritePngAtomic(const cv::Mat& image, const std::filesystem::path& path, const std::vector<int>& params) {
  const std::vector<unsigned char> bytes = EncodePng(image, params);
  WriteFileAtomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace waam::analysis::internal
