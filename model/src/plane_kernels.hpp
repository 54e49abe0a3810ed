// Per-plane kernels of the golden model. The volume stages (cost, aggregate, ca_rule1,
// ca_rule2, wta) run them plane by plane; match() runs the same kernels as a stream over d that
// keeps only a few planes alive, so the working set stays in cache. One implementation, two
// schedules: they cannot disagree.
//
// The loops are written so that the compiler vectorises them (contiguous rows, no branches in
// the inner loops, __restrict pointers); every value is integer, so the result does not depend
// on how they are vectorised.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "stereo/dsi.hpp"
#include "stereo/image.hpp"

namespace stereo::detail {

using Value = Dsi::Value;

// An image split into one contiguous plane per channel.
struct PlanarImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::array<std::vector<std::uint8_t>, 3> planes;

    explicit PlanarImage(const Image& image);
    const std::uint8_t* row(int channel, int y) const {
        return planes[static_cast<std::size_t>(channel)].data() +
               static_cast<std::size_t>(y) * width;
    }
};

// Stage 1 for one disparity: `out` is width*height.
void cost_plane(const PlanarImage& left, const PlanarImage& right, int d, Value* out);

// Stage 2 for one plane, with the scratch rows it needs.
class PlaneAggregator {
  public:
    PlaneAggregator(const std::vector<std::int32_t>& kernel, int width, int height);
    void run(const Value* in, Value* out);

  private:
    std::vector<std::int32_t> kernel_;
    int width_;
    int height_;
    int radius_;
    std::vector<std::int32_t>
        padded_vertical_;  // one vertical-sum row with `radius` zeros each side
    std::vector<std::int32_t> row_sum_;
};

// Stage 3 for plane d. `below` is plane d-1 and `above` plane d+1 of the input volume, nullptr
// where they do not exist.
class PlaneRule1 {
  public:
    PlaneRule1(int width, int height);
    void run(const Value* below, const Value* centre, const Value* above, Value* out);

  private:
    int width_;
    int height_;
    std::vector<std::int32_t> column_sum_;  // 3-row sums of one row, one zero each side
};

// Stage 4 for one plane.
void ca_rule2_plane(const Value* in, int width, int height, Value* out);

// Stage 5, one plane at a time: keep the smallest value and its first d.
void wta_update(const Value* plane, int d, std::size_t size, Value* best, std::uint8_t* label);

}  // namespace stereo::detail
