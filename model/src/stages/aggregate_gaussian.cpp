// Stage 2: separable Gaussian window sum with zero padding, full precision, one rounding shift
// (docs/fixed-point.md). The loops are written so that the compiler vectorises them (contiguous
// rows, no branches inside, __restrict pointers); every value is an integer, so the result does
// not depend on how they are vectorised.
#include <algorithm>

#include "stereo/constants.hpp"
#include "stereo/stages.hpp"

namespace stereo {
namespace {

class GaussianAggregator final : public Aggregator {
  public:
    GaussianAggregator(const std::vector<std::int32_t>& kernel, int width, int height)
        : kernel_(kernel),
          width_(width),
          height_(height),
          radius_(static_cast<int>(kernel.size()) / 2),
          padded_vertical_(static_cast<std::size_t>(width + 2 * radius_), 0),
          row_sum_(static_cast<std::size_t>(width), 0) {}

    int radius() const override { return radius_; }

    void plane(const CostValue* in, CostValue* out) override {
        // Locals, not members: stores through the row pointers could otherwise alias the
        // members, and the compiler would not vectorise the loops.
        const int width = width_;
        const int height = height_;
        const int radius = radius_;
        const std::int32_t round_half = 1 << (fx::kAggShift - 1);
        std::int32_t* __restrict vertical = padded_vertical_.data() + radius;
        std::int32_t* __restrict sum = row_sum_.data();
        for (int y = 0; y < height; ++y) {
            // Vertical pass for this row, zero padding above and below.
            std::fill_n(vertical, width, 0);
            const int first = std::max(-radius, -y);
            const int last = std::min(radius, height - 1 - y);
            for (int j = first; j <= last; ++j) {
                const std::int32_t tap = kernel_[static_cast<std::size_t>(j + radius)];
                const CostValue* __restrict src = in + static_cast<std::size_t>(y + j) * width;
                for (int x = 0; x < width; ++x) {
                    vertical[x] += tap * src[x];
                }
            }
            // Horizontal pass over the zero-padded row, then the single rounding shift.
            std::fill_n(sum, width, 0);
            for (int i = 0; i <= 2 * radius; ++i) {
                const std::int32_t tap = kernel_[static_cast<std::size_t>(i)];
                const std::int32_t* __restrict src = padded_vertical_.data() + i;
                for (int x = 0; x < width; ++x) {
                    sum[x] += tap * src[x];
                }
            }
            CostValue* __restrict dst = out + static_cast<std::size_t>(y) * width;
            for (int x = 0; x < width; ++x) {
                dst[x] = static_cast<CostValue>((sum[x] + round_half) >> fx::kAggShift);
            }
        }
    }

  private:
    std::vector<std::int32_t> kernel_;
    int width_;
    int height_;
    int radius_;
    std::vector<std::int32_t> padded_vertical_;  // one vertical-sum row, `radius` zeros each side
    std::vector<std::int32_t> row_sum_;
};

}  // namespace

std::unique_ptr<Aggregator> make_gaussian_aggregator(const std::vector<std::int32_t>& kernel,
                                                     int width, int height) {
    return std::make_unique<GaussianAggregator>(kernel, width, height);
}

}  // namespace stereo
