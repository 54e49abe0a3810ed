// Stage 4, CA rule 2 (docs/fixed-point.md): a cell with at least fx::kRule2MinCount of its 8
// in-plane neighbours differing from it by less than half its value is divided by 1.3.
#include <algorithm>

#include "stereo/constants.hpp"
#include "stereo/stage_table.hpp"
#include "stereo/stages.hpp"

namespace stereo {
namespace {

class CaRule2 final : public Refiner {
  public:
    CaRule2(int width, int height) : width_(width), height_(height) {}

    bool reads_neighbour_planes() const override { return false; }

    void plane(const CostValue* in, std::span<const NeighbourPlanes> /*neighbours*/,
               CostValue* out) override {
        const int width = width_;
        const int height = height_;
        // A cell on the image border has at most 5 neighbours inside (zero padding never
        // agrees), fewer than kRule2MinCount: border cells pass through unchanged.
        static_assert(fx::kRule2MinCount > 5);
        std::copy_n(in, static_cast<std::size_t>(width) * height, out);
        for (int y = 1; y + 1 < height; ++y) {
            const CostValue* __restrict up = in + static_cast<std::size_t>(y - 1) * width;
            const CostValue* __restrict mid = up + width;
            const CostValue* __restrict down = mid + width;
            CostValue* __restrict dst = out + static_cast<std::size_t>(y) * width;
            for (int x = 1; x + 1 < width; ++x) {
                const int c = mid[x];
                const int neighbours[8] = {up[x - 1],  up[x],       up[x + 1], mid[x - 1],
                                           mid[x + 1], down[x - 1], down[x],   down[x + 1]};
                int count = 0;
                for (const int n : neighbours) {
                    count += fx::agrees(n, c) ? 1 : 0;
                }
                dst[x] = count >= fx::kRule2MinCount
                             ? static_cast<CostValue>(fx::div13(static_cast<std::uint32_t>(c)))
                             : static_cast<CostValue>(c);
            }
        }
    }

  private:
    int width_;
    int height_;
};

}  // namespace

std::unique_ptr<Refiner> make_ca_rule2(int width, int height) {
    return std::make_unique<CaRule2>(width, height);
}

}  // namespace stereo
