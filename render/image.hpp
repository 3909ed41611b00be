// image.hpp — an RGB8 image, PNG output and input (libpng), and the image-quality measures used to compare a lagging
// frame with the synchronized one: PSNR and SSIM.
//
// PSNR = 10 log10(255² / MSE) over all channels (infinite for identical images). SSIM (Wang, Bovik, Sheikh &
// Simoncelli, IEEE TIP 13(4), 2004) on luma Y = 0.299 R + 0.587 G + 0.114 B, over 8×8 windows with stride 4 and
// uniform weights, C1 = (0.01·255)², C2 = (0.03·255)², averaged over windows: 1 for identical images.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace frontsteal::render {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // rows top to bottom, 3 bytes per pixel
  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
  const std::uint8_t* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

// Writes `image` as an 8-bit RGB PNG; throws std::runtime_error naming the path on failure.
void write_png(const Image& image, const std::string& path);

// Reads any PNG as 8-bit RGB; throws std::runtime_error naming the path on failure.
Image read_png(const std::string& path);

double psnr(const Image& a, const Image& b);  // dB; +infinity when identical
double ssim(const Image& a, const Image& b);

// Pixels that differ from `background` (any channel by more than `tolerance`).
std::size_t covered_pixels(const Image& image, const std::uint8_t background[3], int tolerance = 2);

// Intersection over union of the two images' covered pixels (as covered_pixels counts them): 1 when both cover
// the same pixels (or none), 0 when they share none. The render tests' shape check: shading may differ, the
// silhouette may not. Images of the same size; else std::invalid_argument.
double coverage_iou(const Image& a, const Image& b, const std::uint8_t background[3], int tolerance = 2);

}  // namespace frontsteal::render
