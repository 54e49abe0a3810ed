#include "stereo/luma.hpp"

#include <cstdint>

#include "stereo/constants.hpp"

namespace stereo {

Image luma(const Image& image) {
    if (image.channels == 1) {
        return image;
    }
    Image grey(image.width, image.height, 1);
    const std::size_t count = grey.pixels.size();
    const std::uint8_t* src = image.pixels.data();
    for (std::size_t i = 0; i < count; ++i, src += 3) {
        const int sum = fx::kLumaR * src[0] + fx::kLumaG * src[1] + fx::kLumaB * src[2];
        grey.pixels[i] =
            static_cast<std::uint8_t>((sum + (1 << (fx::kLumaShift - 1))) >> fx::kLumaShift);
    }
    return grey;
}

}  // namespace stereo
