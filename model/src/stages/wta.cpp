// Stage 5, winner takes all over a candidate grid with its tie rule (stereo/search.hpp).
#include <cstdlib>

#include "stereo/stages/wta.hpp"

namespace stereo {

std::int64_t tie_key(int d, int v, int prefer_d, int prefer_v) {
    // Lexicographic (|v - pv|, |d - pd|, v, d) packed into one integer.
    return ((static_cast<std::int64_t>(std::abs(v - prefer_v)) * 512 + std::abs(d - prefer_d)) *
                256 +
            (v + 128)) *
               512 +
           d;
}

namespace {

// True when, for a uniform grid, visiting the candidates in order k = j * cols + i already visits
// them in increasing tie key: then "keep the first minimum" is the tie rule.
bool keys_increase_in_order(const CandidateGrid& grid) {
    if (!grid.uniform()) {
        return false;
    }
    std::int64_t previous = -1;
    for (int j = 0; j < grid.rows; ++j) {
        for (int i = 0; i < grid.cols; ++i) {
            const std::int64_t key =
                tie_key(grid.base_d[0] + i, grid.base_v[0] + j, grid.prefer_d[0], grid.prefer_v[0]);
            if (key <= previous) {
                return false;
            }
            previous = key;
        }
    }
    return true;
}

}  // namespace

WinnerTakesAll::WinnerTakesAll(const CandidateGrid& grid)
    : grid_(grid),
      size_(static_cast<std::size_t>(grid.width) * grid.height),
      first_minimum_(keys_increase_in_order(grid)),
      best_(size_),
      best_k_(size_, 0),
      best_key_(first_minimum_ ? 0 : size_) {}

void WinnerTakesAll::update(const CostValue* plane, int i, int j) {
    const auto k = static_cast<std::uint16_t>(j * grid_.cols + i);
    const CostValue* __restrict p = plane;
    CostValue* __restrict best = best_.data();
    std::uint16_t* __restrict label = best_k_.data();
    if (first_minimum_) {
        for (std::size_t q = 0; q < size_; ++q) {
            const bool better = k == 0 || p[q] < best[q];  // strict: ties keep the earlier
            best[q] = better ? p[q] : best[q];
            label[q] = better ? k : label[q];
        }
        return;
    }
    for (std::size_t q = 0; q < size_; ++q) {
        const std::size_t g = grid_.at(q);
        const std::int64_t key =
            tie_key(grid_.base_d[g] + i, grid_.base_v[g] + j, grid_.prefer_d[g], grid_.prefer_v[g]);
        if (k == 0 || p[q] < best[q] || (p[q] == best[q] && key < best_key_[q])) {
            best[q] = p[q];
            best_key_[q] = key;
            label[q] = k;
        }
    }
}

Winners WinnerTakesAll::winners() const {
    Winners out{grid_.width, grid_.height, std::vector<std::int16_t>(size_),
                std::vector<std::int16_t>(size_), std::vector<std::uint8_t>(size_, 0)};
    for (std::size_t q = 0; q < size_; ++q) {
        const std::size_t g = grid_.at(q);
        out.disparity[q] = static_cast<std::int16_t>(grid_.base_d[g] + best_k_[q] % grid_.cols);
        out.vertical[q] = static_cast<std::int16_t>(grid_.base_v[g] + best_k_[q] / grid_.cols);
    }
    return out;
}

}  // namespace stereo
