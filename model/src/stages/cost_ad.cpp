// Stage 1, AD: sum over RGB of |L - R| (docs/fixed-point.md); a grey pixel counts as (g, g, g).
#include <algorithm>

#include "stereo/constants.hpp"
#include "stereo/stages.hpp"

namespace stereo {
namespace {

class AdCost final : public CostFunction {
  public:
    PlanarImage prepare(const Image& image) const override { return PlanarImage(image); }

    void row(const PlanarImage& left, const PlanarImage& right, int y, int yr, int x0, int count,
             int shift, CostValue* out) const override {
        // Three equal channel differences for a grey pixel.
        const int weight = fx::kChannels / left.count();
        CostValue* __restrict dst = out;
        std::fill_n(dst, count, CostValue{0});
        for (int c = 0; c < left.count(); ++c) {
            const std::uint8_t* __restrict l = left.row(c, y) + x0;
            const std::uint8_t* __restrict r = right.row(c, yr) + x0 - shift;
            for (int n = 0; n < count; ++n) {
                const int diff = l[n] - r[n];
                dst[n] = static_cast<CostValue>(dst[n] + weight * (diff < 0 ? -diff : diff));
            }
        }
    }
};

}  // namespace

std::unique_ptr<CostFunction> make_ad_cost() {
    return std::make_unique<AdCost>();
}

}  // namespace stereo
