// Stage 6: the validating winner-takes-all selector (stereo/stages/validate.hpp).
#include "stereo/stages/validate.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "stereo/target_clones.hpp"

namespace stereo {
namespace {

constexpr CostValue kUnset = kNoCandidate;  // an empty slot: above every cost

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
      kept_(size_ * kKept, key(kUnset, 0)),
      before_(size_, kUnset),
      after_(size_, kUnset),
      previous_(size_, kUnset),
      right_cost_(params.left_right ? size_ : 0, kUnset),
      right_label_(params.left_right ? size_ : 0, 0) {
    static_assert(fx::kAggMax < kUnset);
}

// Branchless on purpose (vectorised across pixels): a new winner (c < best cost; equal costs keep
// the smaller k) takes the previous plane's cost as its "before" and clears "after"; the label
// right after the standing winner sets "after"; (c, k) is inserted by min/max. The arrays are
// distinct: __restrict parameters let the compiler vectorise without run-time overlap checks.
// Cloned: the unsigned 32-bit min/max take one instruction from SSE4.1 on, several before.
STEREO_TARGET_CLONES
void ValidatingSelector::update_kept(std::size_t size, int k, const CostValue* __restrict costs,
                                     Key* __restrict slot0, Key* __restrict slot1,
                                     Key* __restrict slot2, Key* __restrict slot3,
                                     CostValue* __restrict before, CostValue* __restrict after,
                                     CostValue* __restrict previous) {
    for (std::size_t q = 0; q < size; ++q) {
        const CostValue c = costs[q];
        const Key incoming = key(c, k);
        const Key best = slot0[q];
        const bool new_winner = incoming < best;
        const bool next_to_winner = key_label(best) + 1 == k && key_cost(best) != kUnset;
        const CostValue before_value = k > 0 ? previous[q] : kUnset;
        before[q] = new_winner ? before_value : before[q];
        after[q] = new_winner ? kUnset : (next_to_winner ? c : after[q]);
        Key carry = incoming;
        Key kept = slot0[q];
        slot0[q] = std::min(kept, carry);
        carry = std::max(kept, carry);
        kept = slot1[q];
        slot1[q] = std::min(kept, carry);
        carry = std::max(kept, carry);
        kept = slot2[q];
        slot2[q] = std::min(kept, carry);
        carry = std::max(kept, carry);
        slot3[q] = std::min(slot3[q], carry);
        previous[q] = c;
    }
}

void ValidatingSelector::update_right(std::size_t size, std::uint16_t label,
                                      const CostValue* __restrict costs,
                                      CostValue* __restrict right_cost,
                                      std::uint16_t* __restrict right_label) {
    for (std::size_t x = 0; x < size; ++x) {
        const CostValue c = costs[x];
        const bool better = c < right_cost[x];
        right_cost[x] = better ? c : right_cost[x];
        right_label[x] = better ? label : right_label[x];
    }
}

void ValidatingSelector::update(const CostValue* plane, int i, int j) {
    if (j != 0 || i < 0 || i >= ndisp_) {
        throw std::invalid_argument("the validating selector runs the 1-D search only");
    }
    static_assert(fx::kMaxDisparities <= 0xFFFF, "a label must fit the key's low half");
    const int k = i;
    Key* const slots = kept_.data();
    update_kept(size_, k, plane, slots, slots + size_, slots + 2 * size_, slots + 3 * size_,
                before_.data(), after_.data(), previous_.data());
    if (params_.left_right) {
        // Right pixel xr = x - d meets left pixel x at this label; planes arrive in increasing k,
        // so a strict comparison keeps the smaller k on ties.
        const int d = min_disp_ + i;
        for (int y = 0; y < height_; ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * width_;
            const int x_begin = std::max(0, d);
            const int x_end = std::min(width_, width_ + d);
            if (x_end > x_begin) {
                const std::size_t right_begin = row + static_cast<std::size_t>(x_begin - d);
                update_right(static_cast<std::size_t>(x_end - x_begin),
                             static_cast<std::uint16_t>(i),
                             plane + row + static_cast<std::size_t>(x_begin),
                             right_cost_.data() + right_begin, right_label_.data() + right_begin);
            }
        }
    }
}

ValidatedDisparity ValidatingSelector::result() const {
    ValidatedDisparity out(width_, height_);
    for (int y = 0; y < height_; ++y) {
        for (int x = 0; x < width_; ++x) {
            const std::size_t q = out.index(x, y);
            const Key best = kept_[q];
            const int winner = key_label(best);
            const int c1 = key_cost(best);
            int c2 = fx::kNoSecondCost;
            for (int slot = 1; slot < kKept; ++slot) {
                const Key candidate = kept_[static_cast<std::size_t>(slot) * size_ + q];
                if (key_cost(candidate) != kUnset && std::abs(key_label(candidate) - winner) > 1) {
                    c2 = key_cost(candidate);
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
            // Both neighbours must be candidates (not so next to a label the ASW matcher excluded).
            if (params_.subpixel && winner > 0 && winner < ndisp_ - 1 && before_[q] != kUnset &&
                after_[q] != kUnset) {
                offset = validation::subpixel_offset(before_[q], c1, after_[q]);
            }
            out.fixed[q] = static_cast<std::int16_t>(d * fx::kSubpixelScale + offset);
        }
    }
    return out;
}

std::vector<std::uint16_t> ValidatingSelector::winner_costs() const {
    std::vector<std::uint16_t> costs(static_cast<std::size_t>(width_) * height_);
    for (std::size_t q = 0; q < costs.size(); ++q) {
        costs[q] = static_cast<std::uint16_t>(key_cost(kept_[q]));
    }
    return costs;
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
