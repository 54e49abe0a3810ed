// Deliberately plain: every value is computed straight from its definition in
// docs/fixed-point.md, with bounds checks in the innermost loops and integer division instead
// of multiply-and-shift. Slow, and meant to be.
#include <cstdlib>

#include "cells.hpp"
#include "stereo/reference.hpp"
#include "stereo/stage_table.hpp"
#include "stereo/stages.hpp"

namespace stereo::naive {
using reference::for_each_cell;
namespace {

// Zero padding: samples outside the plane read as 0.
int sample(const Dsi& dsi, int x, int y, int d) {
    if (x < 0 || y < 0 || x >= dsi.width() || y >= dsi.height()) {
        return 0;
    }
    return dsi.at(x, y, d);
}

bool differs_by_less_than_half(int neighbour, int centre) {
    // |n - c| < c / 2, in exact integers.
    return fx::agrees(neighbour, centre);
}

}  // namespace

Dsi cost(const Image& left, const Image& right, int ndisp) {
    check_pair(left, right);
    Dsi dsi(left.width, left.height, ndisp);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            for (int d = 0; d < ndisp; ++d) {
                if (x - d < 0) {
                    dsi.at(x, y, d) = fx::kCostMax;  // the right pixel is outside the image
                    continue;
                }
                int sum = 0;
                for (int c = 0; c < 3; ++c) {
                    // A grey image has one channel; reading channel 0 three times matches (g,g,g).
                    const int channel = left.channels == 3 ? c : 0;
                    sum += std::abs(left.at(x, y, channel) - right.at(x - d, y, channel));
                }
                dsi.at(x, y, d) = static_cast<Dsi::Value>(sum);
            }
        }
    }
    return dsi;
}

Dsi aggregate(const Dsi& cost, const std::vector<std::int32_t>& kernel) {
    const int radius = static_cast<int>(kernel.size()) / 2;
    const std::int64_t divisor = std::int64_t{1} << fx::kAggShift;
    Dsi out(cost.width(), cost.height(), cost.ndisp());
    for (int d = 0; d < cost.ndisp(); ++d) {
        for (int y = 0; y < cost.height(); ++y) {
            for (int x = 0; x < cost.width(); ++x) {
                std::int64_t sum = 0;
                for (int j = -radius; j <= radius; ++j) {
                    for (int i = -radius; i <= radius; ++i) {
                        const std::int64_t weight =
                            std::int64_t{kernel[i + radius]} * kernel[j + radius];
                        sum += weight * sample(cost, x + i, y + j, d);
                    }
                }
                // Round half up: floor(sum / 2^shift + 1/2).
                out.at(x, y, d) = static_cast<Dsi::Value>((2 * sum + divisor) / (2 * divisor));
            }
        }
    }
    return out;
}

Dsi ca_rule1(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    for_each_cell(dsi.width(), dsi.height(), dsi.ndisp(), [&](int x, int y, int d) {
        const int centre = dsi.at(x, y, d);
        bool fire = false;
        if (d - 1 >= 0 && differs_by_less_than_half(dsi.at(x, y, d - 1), centre)) {
            fire = true;
        }
        if (d + 1 < dsi.ndisp() && differs_by_less_than_half(dsi.at(x, y, d + 1), centre)) {
            fire = true;
        }
        if (!fire) {
            out.at(x, y, d) = static_cast<Dsi::Value>(centre);
            return;
        }
        int sum = 0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                sum += sample(dsi, x + i, y + j, d);
            }
        }
        out.at(x, y, d) = static_cast<Dsi::Value>((2 * sum + 9) / 18);  // round(sum / 9)
    });
    return out;
}

Dsi ca_rule2(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    for_each_cell(dsi.width(), dsi.height(), dsi.ndisp(), [&](int x, int y, int d) {
        const int centre = dsi.at(x, y, d);
        int count = 0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                if (i == 0 && j == 0) {
                    continue;
                }
                if (differs_by_less_than_half(sample(dsi, x + i, y + j, d), centre)) {
                    ++count;
                }
            }
        }
        out.at(x, y, d) = static_cast<Dsi::Value>(count >= 7 ? (20 * centre + 13) / 26
                                                             : centre);  // round(centre / 1.3)
    });
    return out;
}

DisparityMap wta(const Dsi& dsi, const InvalidBorder& border) {
    DisparityMap map(dsi.width(), dsi.height());
    for (int y = 0; y < dsi.height(); ++y) {
        for (int x = 0; x < dsi.width(); ++x) {
            int best = 0;
            for (int d = 1; d < dsi.ndisp(); ++d) {
                if (dsi.at(x, y, d) < dsi.at(x, y, best)) {
                    best = d;
                }
            }
            const int r = border.reach;
            const bool inside = x >= r && y >= r && x < dsi.width() - r && y < dsi.height() - r;
            if (!inside || x - best < r) {
                continue;
            }
            map.disparity[map.index(x, y)] = static_cast<std::uint8_t>(best);
            map.valid[map.index(x, y)] = 1;
        }
    }
    return map;
}

Dsi cost_volume(const std::string& name, const Image& left, const Image& right, int ndisp) {
    if (name == "census") {
        return census::naive::cost(left, right, ndisp);
    }
    if (name == "lcdm") {
        return lcdm::naive::cost(left, right, ndisp);
    }
    if (name == "zncc") {
        return zncc::naive::cost(left, right, ndisp);
    }
    (void)make_cost(name);  // throws on an unknown name
    return naive::cost(left, right, ndisp);
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    // Qualified calls: argument-dependent lookup would also find the optimised stereo:: stages.
    Dsi dsi = naive::aggregate(naive::cost_volume(params.cost, left, right, params.ndisp),
                               gaussian_kernel(params.window, params.sigma));
    if (params.use_ca) {
        dsi = naive::ca_rule2(naive::ca_rule1(dsi));
    }
    return naive::wta(dsi, invalid_border(params));
}

}  // namespace stereo::naive
