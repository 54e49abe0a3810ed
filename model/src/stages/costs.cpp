// The cost functions a matcher can be asked for by name, and the planar image they read.
#include <stdexcept>
#include <string>

#include "stereo/stages.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo {

PlanarImage::PlanarImage(int w, int h, int count)
    : width(w),
      height(h),
      planes(static_cast<std::size_t>(count),
             std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h)) {}

PlanarImage::PlanarImage(const Image& image)
    : PlanarImage(image.width, image.height, image.channels) {
    const std::size_t size = static_cast<std::size_t>(width) * height;
    for (int c = 0; c < image.channels; ++c) {
        auto& plane = planes[static_cast<std::size_t>(c)];
        for (std::size_t i = 0; i < size; ++i) {
            plane[i] = image.pixels[i * image.channels + c];
        }
    }
}

const std::vector<std::string>& cost_names() {
    static const std::vector<std::string> names = {"ad", "census", "lcdm", "zncc"};
    return names;
}

std::unique_ptr<CostFunction> make_cost(std::string_view name) {
    if (name == "ad") {
        return make_ad_cost();
    }
    if (name == "census") {
        return make_census_cost();
    }
    if (name == "lcdm") {
        return make_lcdm_cost(lcdm::kDarkFloor);
    }
    if (name == "zncc") {
        return make_zncc_cost();
    }
    std::string known;
    for (const auto& n : cost_names()) {
        known += (known.empty() ? "" : ", ") + n;
    }
    throw std::invalid_argument("unknown cost \"" + std::string(name) + "\" (known: " + known +
                                ")");
}

}  // namespace stereo
