// The cost functions a matcher can be asked for by name, and the planar image they read.
#include <stdexcept>
#include <string>

#include "stereo/catalogue.hpp"
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
    static const std::vector<std::string> names = catalogue::cost_names();
    return names;
}

std::unique_ptr<CostFunction> make_cost(std::string_view name) {
    switch (catalogue::cost(name).id) {  // throws, naming the known costs, for an unknown name
        case catalogue::Cost::ad:
            return make_ad_cost();
        case catalogue::Cost::census:
            return make_census_cost();
        case catalogue::Cost::lcdm:
            return make_lcdm_cost(lcdm::kDarkFloor);
        case catalogue::Cost::zncc:
            return make_zncc_cost();
    }
    throw std::logic_error("make_cost: a catalogue cost without a factory");
}

}  // namespace stereo
