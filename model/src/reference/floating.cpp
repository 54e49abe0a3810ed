// Double-precision version of the pipeline: the algorithm as the thesis states it, without the
// integer kernel, the rounding shift or the multiply-and-shift reciprocals.
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "cells.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/reference.hpp"

namespace stereo::floating {
using reference::for_each_cell;
namespace {

struct Volume {
    int width, height, ndisp;
    std::vector<double> cells;
    Volume(int w, int h, int n)
        : width(w), height(h), ndisp(n), cells(static_cast<std::size_t>(w) * h * n, 0.0) {}
    double& at(int x, int y, int d) {
        return cells[(static_cast<std::size_t>(d) * height + y) * width + x];
    }
    double at(int x, int y, int d) const {
        return cells[(static_cast<std::size_t>(d) * height + y) * width + x];
    }
    double sample(int x, int y, int d) const {
        return (x < 0 || y < 0 || x >= width || y >= height) ? 0.0 : at(x, y, d);
    }
};

bool differs_by_less_than_half(double neighbour, double centre) {
    return std::abs(neighbour - centre) < centre / 2.0;
}

Volume aggregate(const Dsi& cost, int window, double sigma) {
    const int radius = window / 2;
    std::vector<double> weight(static_cast<std::size_t>(window));
    double total = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        weight[i + radius] = std::exp(-(i * i) / (2.0 * sigma * sigma));
        total += weight[i + radius];
    }
    for (double& w : weight) {
        w /= total;  // exact normalised Gaussian: sum of the 2-D weights is 1
    }
    Volume vertical(cost.width(), cost.height(), cost.ndisp());
    Volume out(cost.width(), cost.height(), cost.ndisp());
    for (int d = 0; d < cost.ndisp(); ++d) {
        for (int y = 0; y < cost.height(); ++y) {
            for (int x = 0; x < cost.width(); ++x) {
                double sum = 0.0;
                for (int j = -radius; j <= radius; ++j) {
                    if (y + j >= 0 && y + j < cost.height()) {
                        sum += weight[j + radius] * cost.at(x, y + j, d);
                    }
                }
                vertical.at(x, y, d) = sum;
            }
        }
        for (int y = 0; y < cost.height(); ++y) {
            for (int x = 0; x < cost.width(); ++x) {
                double sum = 0.0;
                for (int i = -radius; i <= radius; ++i) {
                    sum += weight[i + radius] * vertical.sample(x + i, y, d);
                }
                out.at(x, y, d) = sum;
            }
        }
    }
    return out;
}

Volume ca_rule1(const Volume& in) {
    Volume out = in;
    for_each_cell(in.width, in.height, in.ndisp, [&](int x, int y, int d) {
        const double centre = in.at(x, y, d);
        const bool fire =
            (d > 0 && differs_by_less_than_half(in.at(x, y, d - 1), centre)) ||
            (d + 1 < in.ndisp && differs_by_less_than_half(in.at(x, y, d + 1), centre));
        if (!fire) {
            return;
        }
        double sum = 0.0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                sum += in.sample(x + i, y + j, d);
            }
        }
        out.at(x, y, d) = sum / 9.0;
    });
    return out;
}

Volume ca_rule2(const Volume& in) {
    Volume out = in;
    for_each_cell(in.width, in.height, in.ndisp, [&](int x, int y, int d) {
        const double centre = in.at(x, y, d);
        int count = 0;
        for (int j = -1; j <= 1; ++j) {
            for (int i = -1; i <= 1; ++i) {
                if ((i != 0 || j != 0) &&
                    differs_by_less_than_half(in.sample(x + i, y + j, d), centre)) {
                    ++count;
                }
            }
        }
        if (count >= fx::kRule2MinCount) {
            out.at(x, y, d) = centre / 1.3;
        }
    });
    return out;
}

}  // namespace

DisparityMap match(const Image& left, const Image& right, const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    catalogue::require_cost(params.cost, catalogue::CostUse::floating,
                            "the floating-point reference");
    Volume dsi = aggregate(stereo::cost(left, right, params.ndisp), params.window, params.sigma);
    if (params.use_ca) {
        dsi = ca_rule2(ca_rule1(dsi));
    }
    const InvalidBorder border = invalid_border(params);
    DisparityMap map(left.width, left.height);
    for (int y = 0; y < dsi.height; ++y) {
        for (int x = 0; x < dsi.width; ++x) {
            int best = 0;
            for (int d = 1; d < dsi.ndisp; ++d) {
                if (dsi.at(x, y, d) < dsi.at(x, y, best)) {
                    best = d;
                }
            }
            if (!border.valid(x, y, best, dsi.width, dsi.height)) {
                continue;
            }
            map.disparity[map.index(x, y)] = static_cast<std::uint8_t>(best);
            map.valid[map.index(x, y)] = 1;
        }
    }
    return map;
}

}  // namespace stereo::floating
