#include "plane_kernels.hpp"

#include <algorithm>

#include "stereo/constants.hpp"
#include "stereo/stage_table.hpp"

namespace stereo::detail {

PlanarImage::PlanarImage(const Image& image)
    : width(image.width), height(image.height), channels(image.channels) {
    const std::size_t size = static_cast<std::size_t>(width) * height;
    for (int c = 0; c < channels; ++c) {
        auto& plane = planes[static_cast<std::size_t>(c)];
        plane.resize(size);
        for (std::size_t i = 0; i < size; ++i) {
            plane[i] = image.pixels[i * channels + c];
        }
    }
}

void cost_plane(const PlanarImage& left, const PlanarImage& right, int d, Value* out) {
    const int width = left.width;
    // A grey pixel counts as (g, g, g): three equal channel differences.
    const int weight = 3 / left.channels;
    for (int y = 0; y < left.height; ++y) {
        Value* __restrict row = out + static_cast<std::size_t>(y) * width;
        const int outside = std::min(d, width);
        std::fill_n(row, outside, static_cast<Value>(fx::kCostOutside));
        std::fill(row + outside, row + width, Value{0});
        for (int c = 0; c < left.channels; ++c) {
            const std::uint8_t* __restrict l = left.row(c, y);
            const std::uint8_t* __restrict r = right.row(c, y);
            for (int x = outside; x < width; ++x) {
                const int diff = l[x] - r[x - d];
                row[x] = static_cast<Value>(row[x] + weight * (diff < 0 ? -diff : diff));
            }
        }
    }
}

PlaneAggregator::PlaneAggregator(const std::vector<std::int32_t>& kernel, int width, int height)
    : kernel_(kernel),
      width_(width),
      height_(height),
      radius_(static_cast<int>(kernel.size()) / 2),
      padded_vertical_(static_cast<std::size_t>(width + 2 * radius_), 0),
      row_sum_(static_cast<std::size_t>(width), 0) {}

void PlaneAggregator::run(const Value* in, Value* out) {
    // Locals, not members: stores through the row pointers could otherwise alias the members,
    // and the compiler would not vectorise the loops.
    const int width = width_;
    const int height = height_;
    const int radius = radius_;
    const std::int32_t round_half = 1 << (fx::kAggShift - 1);
    std::int32_t* __restrict vertical = padded_vertical_.data() + radius;
    std::int32_t* __restrict sum = row_sum_.data();
    for (int y = 0; y < height; ++y) {
        // Vertical pass for this row, full precision, zero padding above and below.
        std::fill_n(vertical, width, 0);
        const int first = std::max(-radius, -y);
        const int last = std::min(radius, height - 1 - y);
        for (int j = first; j <= last; ++j) {
            const std::int32_t tap = kernel_[static_cast<std::size_t>(j + radius)];
            const Value* __restrict src = in + static_cast<std::size_t>(y + j) * width;
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
        Value* __restrict dst = out + static_cast<std::size_t>(y) * width;
        for (int x = 0; x < width; ++x) {
            dst[x] = static_cast<Value>((sum[x] + round_half) >> fx::kAggShift);
        }
    }
}

PlaneRule1::PlaneRule1(int width, int height)
    : width_(width), height_(height), column_sum_(static_cast<std::size_t>(width + 2), 0) {}

void PlaneRule1::run(const Value* below, const Value* centre, const Value* above, Value* out) {
    const int width = width_;  // locals, for vectorisation (see PlaneAggregator::run)
    const int height = height_;
    std::int32_t* __restrict columns = column_sum_.data() + 1;  // columns[-1], columns[width] = 0
    for (int y = 0; y < height; ++y) {
        const std::size_t offset = static_cast<std::size_t>(y) * width;
        const Value* __restrict c = centre + offset;
        for (int x = 0; x < width; ++x) {
            columns[x] = c[x];
        }
        if (y > 0) {
            const Value* __restrict up = c - width;
            for (int x = 0; x < width; ++x) {
                columns[x] += up[x];
            }
        }
        if (y + 1 < height) {
            const Value* __restrict down = c + width;
            for (int x = 0; x < width; ++x) {
                columns[x] += down[x];
            }
        }
        // agree(n, c) = 2|n - c| < c; a missing d-neighbour never agrees.
        const Value* __restrict b = below != nullptr ? below + offset : nullptr;
        const Value* __restrict a = above != nullptr ? above + offset : nullptr;
        Value* __restrict dst = out + offset;
        for (int x = 0; x < width; ++x) {
            const int value = c[x];
            const int diff_below = b != nullptr ? b[x] - value : 2 * value;
            const int diff_above = a != nullptr ? a[x] - value : 2 * value;
            const bool fire =
                fx::agrees(value + diff_below, value) || fx::agrees(value + diff_above, value);
            const auto box =
                static_cast<std::uint32_t>(columns[x - 1] + columns[x] + columns[x + 1]);
            dst[x] = fire ? static_cast<Value>(fx::mean9(box)) : static_cast<Value>(value);
        }
    }
}

void ca_rule2_plane(const Value* in, int width, int height, Value* out) {
    // A cell on the image border has at most 5 neighbours inside (zero padding never agrees),
    // fewer than kRule2MinCount: border cells pass through unchanged.
    static_assert(fx::kRule2MinCount > 5);
    std::copy_n(in, static_cast<std::size_t>(width) * height, out);
    for (int y = 1; y + 1 < height; ++y) {
        const Value* __restrict up = in + static_cast<std::size_t>(y - 1) * width;
        const Value* __restrict mid = up + width;
        const Value* __restrict down = mid + width;
        Value* __restrict dst = out + static_cast<std::size_t>(y) * width;
        for (int x = 1; x + 1 < width; ++x) {
            const int c = mid[x];
            const int neighbours[8] = {up[x - 1],  up[x],       up[x + 1], mid[x - 1],
                                       mid[x + 1], down[x - 1], down[x],   down[x + 1]};
            int count = 0;
            for (const int n : neighbours) {
                count += fx::agrees(n, c) ? 1 : 0;
            }
            dst[x] = count >= fx::kRule2MinCount
                         ? static_cast<Value>(fx::div13(static_cast<std::uint32_t>(c)))
                         : static_cast<Value>(c);
        }
    }
}

void wta_update(const Value* plane, int d, std::size_t size, Value* best, std::uint8_t* label) {
    const Value* __restrict p = plane;
    Value* __restrict b = best;
    std::uint8_t* __restrict l = label;
    const auto disparity = static_cast<std::uint8_t>(d);
    for (std::size_t i = 0; i < size; ++i) {
        const bool better = p[i] < b[i];  // strict: ties keep the smaller d
        b[i] = better ? p[i] : b[i];
        l[i] = better ? disparity : l[i];
    }
}

}  // namespace stereo::detail
