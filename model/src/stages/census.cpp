// Census cost plug-in (stereo/stages/census.hpp); naive reference in reference/census_naive.cpp.
#include <bit>

#include "stereo/luma.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/census.hpp"

namespace stereo {
namespace census {

std::vector<std::uint32_t> transform(const Image& image) {
    const Image grey = luma(image);
    const int w = grey.width;
    const int h = grey.height;
    std::vector<std::uint32_t> codes(static_cast<std::size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int centre = grey.at(x, y, 0);
            std::uint32_t code = 0;
            for (int dy = -kRadius; dy <= kRadius; ++dy) {
                for (int dx = -kRadius; dx <= kRadius; ++dx) {
                    if (dx == 0 && dy == 0) {
                        continue;
                    }
                    const int nx = x + dx;
                    const int ny = y + dy;
                    const bool inside = nx >= 0 && nx < w && ny >= 0 && ny < h;
                    code = (code << 1) | (inside && grey.at(nx, ny, 0) < centre ? 1U : 0U);
                }
            }
            codes[static_cast<std::size_t>(y) * w + x] = code;
        }
    }
    return codes;
}

}  // namespace census

namespace {

class CensusCost final : public CostFunction {
  public:
    // The code's three bytes as three planes.
    PlanarImage prepare(const Image& image) const override {
        const auto codes = census::transform(image);
        PlanarImage planes(image.width, image.height, 3);
        for (std::size_t p = 0; p < codes.size(); ++p) {
            for (std::size_t b = 0; b < 3; ++b) {
                planes.planes[b][p] = static_cast<std::uint8_t>(codes[p] >> (8 * b));
            }
        }
        return planes;
    }

    void row(const PlanarImage& left, const PlanarImage& right, int y, int yr, int x0, int count,
             int shift, CostValue* out) const override {
        for (int n = 0; n < count; ++n) {
            int distance = 0;
            for (int b = 0; b < 3; ++b) {
                const auto diff = static_cast<unsigned>(left.row(b, y)[x0 + n] ^
                                                        right.row(b, yr)[x0 + n - shift]);
                distance += std::popcount(diff);
            }
            out[n] = static_cast<CostValue>(distance * census::kWeight);
        }
    }
};

}  // namespace

std::unique_ptr<CostFunction> make_census_cost() {
    return std::make_unique<CensusCost>();
}

}  // namespace stereo
