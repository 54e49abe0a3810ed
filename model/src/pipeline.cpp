#include "stereo/pipeline.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace stereo {
namespace {

using Value = Dsi::Value;

std::string size_text(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

void check_kernel(const std::vector<std::int32_t>& kernel) {
    std::int64_t sum = 0;
    for (const auto tap : kernel) {
        if (tap < 0) {
            throw std::invalid_argument("kernel taps must be non-negative");
        }
        sum += tap;
    }
    if (kernel.empty() || kernel.size() % 2 == 0 || sum != fx::kKernelSum) {
        throw std::invalid_argument("kernel must have an odd number of taps summing to " +
                                    std::to_string(fx::kKernelSum));
    }
}

// 2 * |a - b| < c : "differs from the centre by less than half of the centre's value",
// exact in integers.
bool close_to(int neighbour, int centre) { return 2 * std::abs(neighbour - centre) < centre; }

}  // namespace

void check_pair(const Image& left, const Image& right) {
    if (left.empty() || right.empty()) {
        throw std::invalid_argument("left and right images must not be empty");
    }
    if (left.width != right.width || left.height != right.height) {
        throw std::invalid_argument("left image is " + size_text(left.width, left.height) +
                                    " but right image is " + size_text(right.width, right.height));
    }
    if (left.channels != right.channels) {
        throw std::invalid_argument("left image has " + std::to_string(left.channels) +
                                    " channel(s) but right image has " +
                                    std::to_string(right.channels));
    }
}

InvalidBorder invalid_border(const MatchParams& params) {
    // Aggregation reaches `radius` pixels out; the CA rules one pixel more (3x3).
    return {params.window / 2 + (params.use_ca ? 1 : 0)};
}

void validate(const MatchParams& params, int width, int height) {
    if (params.ndisp < 1 || params.ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp must be in [1, " + std::to_string(fx::kMaxDisparities) +
                                    "], got " + std::to_string(params.ndisp));
    }
    if (params.ndisp >= width) {
        throw std::invalid_argument("ndisp " + std::to_string(params.ndisp) +
                                    " must be smaller than the image width " +
                                    std::to_string(width));
    }
    (void)gaussian_kernel(params.window, params.sigma);  // throws on a bad window or sigma
    const InvalidBorder border = invalid_border(params);
    if (width <= 2 * border.reach || height <= 2 * border.reach) {
        throw std::invalid_argument("image " + size_text(width, height) +
                                    " is too small for ndisp " + std::to_string(params.ndisp) +
                                    " and window " + std::to_string(params.window) +
                                    ": no pixel would be valid");
    }
}

Dsi cost(const Image& left, const Image& right, int ndisp) {
    check_pair(left, right);
    if (ndisp < 1 || ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp out of range: " + std::to_string(ndisp));
    }
    const int width = left.width;
    const int height = left.height;
    const int channels = left.channels;
    // A grey pixel counts as (g, g, g): three equal channel differences.
    const int weight = fx::kChannels / channels;
    Dsi dsi(width, height, ndisp);
    for (int d = 0; d < ndisp; ++d) {
        for (int y = 0; y < height; ++y) {
            std::fill_n(&dsi.at(0, y, d), std::min(d, width), static_cast<Value>(fx::kCostOutside));
        }
        for (int y = 0; y < height; ++y) {
            const std::uint8_t* left_row = &left.pixels[static_cast<std::size_t>(y) * width * channels];
            const std::uint8_t* right_row =
                &right.pixels[static_cast<std::size_t>(y) * width * channels];
            Value* out = &dsi.at(0, y, d);
            for (int x = d; x < width; ++x) {
                int sum = 0;
                for (int c = 0; c < channels; ++c) {
                    sum += std::abs(left_row[x * channels + c] - right_row[(x - d) * channels + c]);
                }
                out[x] = static_cast<Value>(weight * sum);
            }
        }
    }
    return dsi;
}

Dsi aggregate(const Dsi& cost, const std::vector<std::int32_t>& kernel) {
    check_kernel(kernel);
    const int width = cost.width();
    const int height = cost.height();
    const int radius = static_cast<int>(kernel.size()) / 2;
    const std::int32_t round_half = 1 << (fx::kAggShift - 1);
    Dsi out(width, height, cost.ndisp());

    // Separable form: vertical pass then horizontal pass, both in full precision, then one
    // rounding shift. Equal to the direct 2-D sum because the 2-D kernel is the outer product.
    std::vector<std::int32_t> vertical(cost.plane_size());
    std::vector<std::int32_t> padded_row(static_cast<std::size_t>(width + 2 * radius), 0);
    for (int d = 0; d < cost.ndisp(); ++d) {
        const auto in = cost.plane(d);
        std::fill(vertical.begin(), vertical.end(), 0);
        for (int y = 0; y < height; ++y) {
            std::int32_t* acc = &vertical[static_cast<std::size_t>(y) * width];
            for (int j = -radius; j <= radius; ++j) {
                const int source_y = y + j;
                if (source_y < 0 || source_y >= height) {
                    continue;  // zero padding
                }
                const std::int32_t tap = kernel[static_cast<std::size_t>(j + radius)];
                const Value* src = &in[static_cast<std::size_t>(source_y) * width];
                for (int x = 0; x < width; ++x) {
                    acc[x] += tap * src[x];
                }
            }
        }
        auto result = out.plane(d);
        for (int y = 0; y < height; ++y) {
            std::copy_n(&vertical[static_cast<std::size_t>(y) * width], width,
                        padded_row.begin() + radius);
            Value* dst = &result[static_cast<std::size_t>(y) * width];
            for (int x = 0; x < width; ++x) {
                std::int32_t sum = 0;
                for (int i = 0; i <= 2 * radius; ++i) {
                    sum += kernel[static_cast<std::size_t>(i)] * padded_row[x + i];
                }
                dst[x] = static_cast<Value>((sum + round_half) >> fx::kAggShift);
            }
        }
    }
    return out;
}

Dsi ca_rule1(const Dsi& dsi) {
    const int width = dsi.width();
    const int height = dsi.height();
    const int ndisp = dsi.ndisp();
    Dsi out = dsi;
    std::vector<std::int32_t> column_sum(dsi.plane_size());
    for (int d = 0; d < ndisp; ++d) {
        const auto in = dsi.plane(d);
        // 3-row sums with zero padding; the 3-column sum is taken below where needed.
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                std::int32_t sum = 0;
                for (int j = std::max(0, y - 1); j <= std::min(height - 1, y + 1); ++j) {
                    sum += in[static_cast<std::size_t>(j) * width + x];
                }
                column_sum[static_cast<std::size_t>(y) * width + x] = sum;
            }
        }
        auto result = out.plane(d);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const int centre = dsi.at(x, y, d);
                const bool agree_below = d > 0 && close_to(dsi.at(x, y, d - 1), centre);
                const bool agree_above = d + 1 < ndisp && close_to(dsi.at(x, y, d + 1), centre);
                if (!agree_below && !agree_above) {
                    continue;
                }
                const std::int32_t* row = &column_sum[static_cast<std::size_t>(y) * width];
                std::int32_t sum9 = row[x];
                if (x > 0) {
                    sum9 += row[x - 1];
                }
                if (x + 1 < width) {
                    sum9 += row[x + 1];
                }
                result[static_cast<std::size_t>(y) * width + x] =
                    static_cast<Value>(fx::mean9(static_cast<std::uint32_t>(sum9)));
            }
        }
    }
    return out;
}

Dsi ca_rule2(const Dsi& dsi) {
    const int width = dsi.width();
    const int height = dsi.height();
    Dsi out = dsi;
    for (int d = 0; d < dsi.ndisp(); ++d) {
        const auto in = dsi.plane(d);
        auto result = out.plane(d);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const int centre = in[static_cast<std::size_t>(y) * width + x];
                int count = 0;
                for (int j = std::max(0, y - 1); j <= std::min(height - 1, y + 1); ++j) {
                    for (int i = std::max(0, x - 1); i <= std::min(width - 1, x + 1); ++i) {
                        if ((i != x || j != y) &&
                            close_to(in[static_cast<std::size_t>(j) * width + i], centre)) {
                            ++count;
                        }
                    }
                }
                // Outside the image the DSI is zero-padded; a zero never counts (2*c < c is false).
                if (count >= fx::kRule2MinCount) {
                    result[static_cast<std::size_t>(y) * width + x] =
                        static_cast<Value>(fx::div13(static_cast<std::uint32_t>(centre)));
                }
            }
        }
    }
    return out;
}

DisparityMap wta(const Dsi& dsi, const InvalidBorder& border) {
    const int width = dsi.width();
    const int height = dsi.height();
    std::vector<Value> best_value(dsi.plane(0).begin(), dsi.plane(0).end());
    std::vector<std::uint8_t> best_label(dsi.plane_size(), 0);
    for (int d = 1; d < dsi.ndisp(); ++d) {
        const auto plane = dsi.plane(d);
        for (std::size_t i = 0; i < plane.size(); ++i) {
            if (plane[i] < best_value[i]) {  // strict: ties keep the smaller d
                best_value[i] = plane[i];
                best_label[i] = static_cast<std::uint8_t>(d);
            }
        }
    }
    DisparityMap map(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = map.index(x, y);
            if (border.valid(x, y, best_label[i], width, height)) {
                map.disparity[i] = best_label[i];
                map.valid[i] = 1;
            }
        }
    }
    return map;
}

DisparityMap match(const Image& left, const Image& right, const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    Dsi dsi = aggregate(cost(left, right, params.ndisp), gaussian_kernel(params.window, params.sigma));
    if (params.use_ca) {
        dsi = ca_rule2(ca_rule1(dsi));
    }
    return wta(dsi, invalid_border(params));
}

}  // namespace stereo
