// libFuzzer target: the PNG reader (analysis/png_file.h, libpng's simplified API) into grey, BGR and BGRA images.
// Any input may be refused with waam::InputError; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "analysis/png_file.h"
#include "fuzz/fuzz_input.h"
#include "models/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const int channels : {1, 3, 4}) {
    try {
      const cv::Mat image = waam::analysis::internal::DecodePng(bytes, channels, "fuzz.png");
      // An accepted picture has the asked channels and a size within the limit.
      if (image.channels() != channels || image.empty() ||
          static_cast<long long>(image.rows) * image.cols > waam::analysis::internal::kMaxPngPixels) {
        std::abort();
      }
    } catch (const waam::InputError& e) {
      waam::fuzz::CheckOneLine(e);
    }
  }
  return 0;
}
