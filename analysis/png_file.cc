// PNG files through libpng's simplified API (png_image_*: libpng 1.6 handles its own setjmp/longjmp), written
// atomically by models/core/files.h.
#include "analysis/png_file.h"

#include <png.h>

#include <cctype>
#include <cstdint>
#include <cstring>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis::internal {
namespace {

bool SupportedChannels(int channels) { return channels == 1 || channels == 3 || channels == 4; }

// The simplified API's 8-bit format with OpenCV's channel order for `channels` = 1, 3 or 4 (PNG_FORMAT_GRAY is 0).
png_uint_32 FormatOf(int channels) {
  WAAM_DEMAND(SupportedChannels(channels));
  return channels == 1 ? PNG_FORMAT_GRAY : channels == 3 ? PNG_FORMAT_BGR : PNG_FORMAT_BGRA;
}

// Refuses a chunk whose declared length (PNG spec sec. 5.3: at most 2^31 - 1) runs past the end of `bytes`, before
// libpng sees it: libpng allocates a chunk's buffer from its declared length, so a 400-byte file declaring a 1 GiB
// text chunk would allocate and clear 1 GiB before finding the file short. Stops at IEND; a file that is not a PNG
// is left to libpng to name.
void CheckChunkLengths(std::string_view bytes, const std::string& name) {
  constexpr std::size_t kSignature = 8;
  if (bytes.size() < kSignature || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, kSignature) != 0) {
    return;
  }
  std::size_t at = kSignature;
  while (at + 8 <= bytes.size()) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
    const std::uint32_t length = (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
    std::string type(bytes.substr(at + 4, 4));
    for (char& c : type) c = std::isalpha(static_cast<unsigned char>(c)) ? c : '?';  // the message stays one line
    const std::size_t left = at + 12 <= bytes.size() ? bytes.size() - at - 12 : 0;  // besides length, type, CRC
    WAAM_THROW_UNLESS(at + 12 <= bytes.size() && length <= left,
                      name << ": corrupt PNG (chunk '" << type << "' at byte " << at << " declares " << length
                           << " bytes, " << left << " follow)");
    if (type == "IEND") return;
    at += 12 + std::size_t{length};
  }
}

png_image NewImage() {
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  return image;
}

}  // namespace

std::vector<unsigned char> EncodePng(const cv::Mat& image) {
  WAAM_DEMAND(!image.empty() && image.depth() == CV_8U && SupportedChannels(image.channels()));
  png_image png = NewImage();
  png.width = static_cast<png_uint_32>(image.cols);
  png.height = static_cast<png_uint_32>(image.rows);
  png.format = FormatOf(image.channels());
  // The bound of the simplified API (uncompressed size plus chunk overhead): one encoding, no second pass.
  std::vector<unsigned char> bytes(PNG_IMAGE_PNG_SIZE_MAX(png));
  png_alloc_size_t size = bytes.size();
  const auto stride = static_cast<png_int_32>(image.step1());  // in components, as png_image expects
  const int written = png_image_write_to_memory(&png, bytes.data(), &size, 0, image.data, stride, nullptr);
  if (!written) png_image_free(&png);
  WAAM_DEMAND(written && size <= bytes.size());
  bytes.resize(size);
  return bytes;
}

void WritePngAtomic(const cv::Mat& image, const std::filesystem::path& path) {
  const std::vector<unsigned char> bytes = EncodePng(image);
  WriteFileAtomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

cv::Mat DecodePng(std::string_view bytes, int channels, const std::string& name) {
  WAAM_DEMAND(SupportedChannels(channels));
  CheckChunkLengths(bytes, name);
  png_image png = NewImage();
  WAAM_THROW_UNLESS(png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()),
                    name << ": not a readable PNG (" << png.message << ")");
  const long long pixels = static_cast<long long>(png.width) * png.height;
  if (pixels > kMaxPngPixels) {
    png_image_free(&png);
    WAAM_THROW_UNLESS(false, name << ": PNG of " << png.width << " x " << png.height << " pixels is over the limit of "
                                  << kMaxPngPixels << " pixels");
  }
  png.format = FormatOf(channels);
  cv::Mat image = cv::Mat::zeros(static_cast<int>(png.height), static_cast<int>(png.width), CV_8UC(channels));
  const auto stride = static_cast<png_int_32>(image.step1());
  // finish_read frees `png` whether it succeeds or not.
  WAAM_THROW_UNLESS(png_image_finish_read(&png, nullptr, image.data, stride, nullptr),
                    name << ": corrupt PNG (" << png.message << ")");
  return image;
}

cv::Mat ReadPng(const std::filesystem::path& path, int channels) {
  return DecodePng(ReadFile(path), channels, path.string());
}

}  // namespace waam::analysis::internal
