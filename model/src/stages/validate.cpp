// Stage 6: the validating winner-takes-all selector (stereo/stages/validate.hpp).
#include "stereo/stages/validate.hpp"

#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace stereo {
namespace {

constexpr CostValue kUnset = std::numeric_limits<CostValue>::max();  // above every cost

}  // namespace

ValidatingSelector::ValidatingSelector(int width, int height, int ndisp, int min_disp,
                                       const ValidationParams& params, const InvalidBorder& border)
    : width_(width),
      height_(height),
      ndisp_(ndisp),
      min_disp_(min_disp),
      params_(params),
      border_(border),
      size_(static_cast<std::size_t>(width) * height),
      best_cost_(size_ * kKept, kUnset),
      best_label_(size_ * kKept, 0),
      before_(size_, kUnset),
      after_(size_, kUnset),
      previous_(size_, kUnset),
      right_cost_(params.left_right ? size_ : 0, kUnset),
      right_label_(params.left_right ? size_ : 0, 0) {
    static_assert(fx::kAggMax < kUnset);
}

void ValidatingSelector::update(const CostValue* plane, int i, int j) {
    if (j != 0 || i < 0 || i >= ndisp_) {
        throw std::invalid_argument("the validating selector runs the 1-D search only");
    }
    const auto k = static_cast<std::uint16_t>(i);
    for (std::size_t q = 0; q < size_; ++q) {
        const CostValue c = plane[q];
        CostValue* cost = &best_cost_[q * kKept];
        std::uint16_t* label = &best_label_[q * kKept];
        if (c < cost[0]) {  // a new winner (strict: ties keep the smaller k)
            before_[q] = k > 0 ? previous_[q] : kUnset;
            after_[q] = kUnset;
        } else if (k == label[0] + 1 && cost[0] != kUnset) {
            after_[q] = c;
        }
        // Insert (c, k) into the ascending list; an equal cost stays behind the earlier k.
        if (c < cost[kKept - 1]) {
            int slot = kKept - 1;
            while (slot > 0 && c < cost[slot - 1]) {
                cost[slot] = cost[slot - 1];
                label[slot] = label[slot - 1];
                --slot;
            }
            cost[slot] = c;
            label[slot] = k;
        }
        previous_[q] = c;
    }
    if (params_.left_right) {
        // Right pixel xr = x - d meets left pixel x at this label; planes arrive in increasing k,
        // so a strict comparison keeps the smaller k on ties.
        const int d = min_disp_ + i;
        for (int y = 0; y < height_; ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * width_;
            const int x_begin = std::max(0, d);
            const int x_end = std::min(width_, width_ + d);
            for (int x = x_begin; x < x_end; ++x) {
                const std::size_t r = row + static_cast<std::size_t>(x - d);
                const CostValue c = plane[row + static_cast<std::size_t>(x)];
                if (c < right_cost_[r]) {
                    right_cost_[r] = c;
                    right_label_[r] = k;
                }
            }
        }
    }
}

ValidatedDisparity ValidatingSelector::result() const {
    ValidatedDisparity out(width_, height_);
    for (int y = 0; y < height_; ++y) {
        for (int x = 0; x < width_; ++x) {
            const std::size_t q = out.index(x, y);
            const CostValue* cost = &best_cost_[q * kKept];
            const std::uint16_t* label = &best_label_[q * kKept];
            const int winner = label[0];
            const int c1 = cost[0];
            int c2 = fx::kNoSecondCost;
            for (int slot = 1; slot < kKept; ++slot) {
                if (cost[slot] != kUnset && std::abs(label[slot] - winner) > 1) {
                    c2 = cost[slot];
                    break;
                }
            }
            out.certainty[q] = static_cast<std::uint8_t>(validation::certainty(c1, c2));
            const int d = min_disp_ + winner;
            std::uint8_t reason = fx::kReasonValid;
            if (!border_.valid(x, y, d, width_, height_)) {
                reason = fx::kReasonBorder;
            } else if (params_.uniqueness &&
                       !validation::unique(c1, c2, params_.uniqueness_ratio)) {
                reason = fx::kReasonUniqueness;
            } else if (params_.left_right &&
                       std::abs(winner - right_label_[static_cast<std::size_t>(y) * width_ +
                                                      static_cast<std::size_t>(x - d)]) >
                           params_.lr_tolerance) {
                reason = fx::kReasonLeftRight;
            }
            out.reason[q] = reason;
            if (reason != fx::kReasonValid) {
                continue;
            }
            int offset = 0;
            if (params_.subpixel && winner > 0 && winner < ndisp_ - 1) {
                offset = validation::subpixel_offset(before_[q], c1, after_[q]);
            }
            out.fixed[q] = static_cast<std::int16_t>(d * fx::kSubpixelScale + offset);
        }
    }
    return out;
}

DisparityMap to_label_map(const ValidatedDisparity& validated) {
    DisparityMap map(validated.width, validated.height);
    for (std::size_t q = 0; q < validated.fixed.size(); ++q) {
        if (!validated.valid(q)) {
            continue;
        }
        // Nearest integer, halves up: floor((fixed + 8) / 16) with an arithmetic shift.
        const int rounded = (validated.fixed[q] + fx::kSubpixelScale / 2) >> fx::kSubpixelBits;
        if (rounded >= 0 && rounded < fx::kMaxDisparities) {
            map.disparity[q] = static_cast<std::uint8_t>(rounded);
            map.valid[q] = 1;
        }
    }
    return map;
}

}  // namespace stereo
