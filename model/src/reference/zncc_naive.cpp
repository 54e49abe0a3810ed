// Naive reference of the ZNCC cost (stereo/stages/zncc.hpp): the 15x15 window of every cell is
// summed directly, pixel by pixel with bounds checks; the square root is found bit by bit.
#include <cstdint>

#include "cells.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/reference.hpp"
#include "stereo/stages/zncc.hpp"

namespace stereo::zncc::naive {
namespace {

std::uint64_t square_root(std::uint64_t value) {
    std::uint64_t root = 0;
    for (std::uint64_t bit = std::uint64_t{1} << 31; bit > 0; bit >>= 1) {
        const std::uint64_t candidate = root + bit;
        if (candidate * candidate <= value) {
            root = candidate;
        }
    }
    return root;
}

bool inside(const Image& image, int x, int y) {
    return x >= 0 && y >= 0 && x < image.width && y < image.height;
}

}  // namespace

Dsi cost(const Image& left, const Image& right, int ndisp, int min_disp) {
    check_pair(left, right);
    const Image l = edge_frontend::naive::luma(left);
    const Image r = edge_frontend::naive::luma(right);
    return reference::pixel_cost_volume(
        left, ndisp, min_disp, fx::kCostOutside, [&](int x, int y, int right_x) {
            const int d = x - right_x;
            std::int64_t n = 0, sl = 0, sr = 0, sll = 0, srr = 0, slr = 0;
            for (int j = -kRadius; j <= kRadius; ++j) {
                for (int i = -kRadius; i <= kRadius; ++i) {
                    if (!inside(l, x + i, y + j) || !inside(r, x + i - d, y + j)) {
                        continue;
                    }
                    const std::int64_t a = l.at(x + i, y + j, 0);
                    const std::int64_t b = r.at(x + i - d, y + j, 0);
                    ++n;
                    sl += a;
                    sr += b;
                    sll += a * a;
                    srr += b * b;
                    slr += a * b;
                }
            }
            const std::int64_t num = n * slr - sl * sr;
            const std::int64_t vl = n * sll - sl * sl;
            const std::int64_t vr = n * srr - sr * sr;
            const auto den = static_cast<std::int64_t>(
                square_root(static_cast<std::uint64_t>(vl) * static_cast<std::uint64_t>(vr)));
            std::int64_t value = kFlatCost;
            if (den != 0) {
                const std::int64_t numerator = (den - num) * fx::kCostMax + den;
                value = numerator < 0 ? 0 : numerator / (2 * den);
                value = value > fx::kCostMax ? fx::kCostMax : value;
            }
            return value;
        });
}

}  // namespace stereo::zncc::naive
