// The winner-takes-all stage: the model's Selector over a grid of candidates with its tie rule.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "stereo/candidates.hpp"
#include "stereo/stages.hpp"

namespace stereo {

// The winner of every pixel: displacement (d, v), valid or not.
struct Winners {
    int width = 0;
    int height = 0;
    std::vector<std::int16_t> disparity;
    std::vector<std::int16_t> vertical;
    std::vector<std::uint8_t> valid;  // filled by the caller's border rule

    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
    bool operator==(const Winners&) const = default;
};

// The model's selector: winner takes all over the grid with its tie rule.
class WinnerTakesAll final : public Selector {
  public:
    explicit WinnerTakesAll(const CandidateGrid& grid);
    void update(const CostValue* plane, int i, int j) override;
    Winners winners() const;  // valid left all 0

  private:
    const CandidateGrid& grid_;
    std::size_t size_;
    bool first_minimum_;  // candidate order already is the tie order: keep the first minimum
    std::vector<CostValue> best_;
    std::vector<std::uint16_t> best_k_;  // k = j * cols + i
    std::vector<std::int64_t> best_key_;
};

}  // namespace stereo
