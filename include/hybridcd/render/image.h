// SPDX-License-Identifier: BSD-3-Clause
// An 8-bit RGB picture and its PNG encoding.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace hcd::render
{
/// A colour with components in [0, 1].
struct Rgb
{
    double r = 0.0, g = 0.0, b = 0.0;
};

/// Rows top to bottom, pixels left to right, three bytes (R, G, B) each.
struct Image
{
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  ///< width * height * 3 bytes

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h) * 3, 0) {}

    const std::uint8_t *at(int x, int y) const { return &pixels[(std::size_t(y) * std::size_t(width) + x) * 3]; }
    std::uint8_t *at(int x, int y) { return &pixels[(std::size_t(y) * std::size_t(width) + x) * 3]; }
};

/// The image as a PNG file's bytes (stb_image_write; the same image always gives the same bytes).
std::string encodePng(const Image &image);

/// Writes encodePng(image) to `path` atomically (io/atomic_file.h); throws InputError naming it.
void writePng(const Image &image, const std::string &path);
}  // namespace hcd::render
