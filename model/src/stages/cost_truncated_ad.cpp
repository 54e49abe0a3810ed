// Stage 1 of the edge front end: min(AD, truncation) (docs/avoidance.md).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "stereo/constants.hpp"
#include "stereo/stages.hpp"

namespace stereo {
namespace {

class TruncatedAdCost final : public CostFunction {
  public:
    explicit TruncatedAdCost(int truncation) : ad_(make_ad_cost()), truncation_(truncation) {}

    PlanarImage prepare(const Image& image) const override { return ad_->prepare(image); }

    void row(const PlanarImage& left, const PlanarImage& right, int y, int yr, int x0, int count,
             int shift, CostValue* out) const override {
        ad_->row(left, right, y, yr, x0, count, shift, out);
        const auto cap = static_cast<CostValue>(truncation_);
        for (int n = 0; n < count; ++n) {
            out[n] = std::min(out[n], cap);
        }
    }

  private:
    std::unique_ptr<CostFunction> ad_;
    int truncation_;
};

}  // namespace

std::unique_ptr<CostFunction> make_truncated_ad_cost(int truncation) {
    if (truncation < 0 || truncation > fx::kCostMax) {
        throw std::invalid_argument("truncation must be in [0, " + std::to_string(fx::kCostMax) +
                                    "], got " + std::to_string(truncation));
    }
    return std::make_unique<TruncatedAdCost>(truncation);
}

}  // namespace stereo
