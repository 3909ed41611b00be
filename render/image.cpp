#include "render/image.hpp"

#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>

namespace frontsteal::render {

void write_png(const Image& image, const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) throw std::runtime_error("cannot write " + path);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: out of memory writing " + path);
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: failed writing " + path);
  }
  png_init_io(png, file.get());
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, const_cast<png_bytep>(image.pixel(0, y)));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

Image read_png(const std::string& path) {
  // libpng's simplified API: any PNG (palette, grey, 16-bit, alpha) converted to 8-bit RGB.
  png_image info{};
  info.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&info, path.c_str())) {
    throw std::runtime_error("cannot read PNG " + path + ": " + info.message);
  }
  info.format = PNG_FORMAT_RGB;
  Image image(static_cast<int>(info.width), static_cast<int>(info.height));
  if (!png_image_finish_read(&info, nullptr, image.rgb.data(), 0, nullptr)) {
    png_image_free(&info);
    throw std::runtime_error("cannot decode PNG " + path + ": " + info.message);
  }
  return image;
}

namespace {
void require_same_size(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) throw std::invalid_argument("images of different sizes");
}
}  // namespace

double psnr(const Image& a, const Image& b) {
  require_same_size(a, b);
  double sum = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    const double d = static_cast<double>(a.rgb[i]) - b.rgb[i];
    sum += d * d;
  }
  if (sum == 0) return std::numeric_limits<double>::infinity();
  const double mse = sum / static_cast<double>(a.rgb.size());
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

double ssim(const Image& a, const Image& b) {
  require_same_size(a, b);
  const auto luma = [](const Image& im, int x, int y) {
    const std::uint8_t* p = im.pixel(x, y);
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
  };
  constexpr int kWindow = 8, kStride = 4;
  constexpr double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  double total = 0;
  int windows = 0;
  for (int y0 = 0; y0 + kWindow <= a.height; y0 += kStride) {
    for (int x0 = 0; x0 + kWindow <= a.width; x0 += kStride) {
      double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      for (int y = y0; y < y0 + kWindow; ++y) {
        for (int x = x0; x < x0 + kWindow; ++x) {
          const double p = luma(a, x, y), q = luma(b, x, y);
          sa += p;
          sb += q;
          saa += p * p;
          sbb += q * q;
          sab += p * q;
        }
      }
      const double n = kWindow * kWindow;
      const double ma = sa / n, mb = sb / n;
      const double va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
      total += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  }
  return windows > 0 ? total / windows : 1.0;
}

std::size_t covered_pixels(const Image& image, const std::uint8_t background[3], int tolerance) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    bool differs = false;
    for (int c = 0; c < 3; ++c)
      differs = differs || std::abs(static_cast<int>(image.rgb[i + c]) - background[c]) > tolerance;
    n += differs;
  }
  return n;
}

double coverage_iou(const Image& a, const Image& b, const std::uint8_t background[3], int tolerance) {
  require_same_size(a, b);
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i + 2 < a.rgb.size(); i += 3) {
    bool in_a = false, in_b = false;
    for (int c = 0; c < 3; ++c) {
      in_a = in_a || std::abs(a.rgb[i + c] - background[c]) > tolerance;
      in_b = in_b || std::abs(b.rgb[i + c] - background[c]) > tolerance;
    }
    both += in_a && in_b;
    either += in_a || in_b;
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

}  // namespace frontsteal::render
