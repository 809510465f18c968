// SPDX-License-Identifier: BSD-3-Clause
#include "hybridcd/render/image.h"

#include "hybridcd/io/atomic_file.h"

#include <stb_image_write.h>

#include <stdexcept>

namespace hcd::render
{
namespace
{
void appendBytes(void *context, void *data, int size)
{
    static_cast<std::string *>(context)->append(static_cast<const char *>(data), std::size_t(size));
}
}  // namespace

std::string encodePng(const Image &image)
{
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
        throw std::invalid_argument("encodePng: the image has no pixels or a wrong pixel count");
    std::string bytes;
    if (!stbi_write_png_to_func(appendBytes, &bytes, image.width, image.height, 3, image.pixels.data(),
                                image.width * 3))
        throw std::runtime_error("encodePng: PNG encoding failed");
    return bytes;
}

void writePng(const Image &image, const std::string &path)
{
    const std::string bytes = encodePng(image);
    AtomicFile file(path);
    file.stream().write(bytes.data(), std::streamsize(bytes.size()));
    file.commit();
}
}  // namespace hcd::render
