// Stage 3, CA rule 1 (docs/fixed-point.md): a cell whose neighbour before or after it along a
// search axis differs from it by less than half its value becomes the rounded mean of its 3x3
// in-plane neighbourhood. A missing neighbour never agrees.
#include <algorithm>

#include "stereo/constants.hpp"
#include "stereo/stage_table.hpp"
#include "stereo/stages.hpp"

namespace stereo {
namespace {

class CaRule1 final : public Refiner {
  public:
    CaRule1(int width, int height)
        : width_(width),
          height_(height),
          column_sum_(static_cast<std::size_t>(width + 2), 0),
          other_axis_(static_cast<std::size_t>(width) * height) {}

    bool reads_neighbour_planes() const override { return true; }

    void plane(const CostValue* centre, std::span<const NeighbourPlanes> neighbours,
               CostValue* out) override {
        run(centre, neighbours.empty() ? NeighbourPlanes{} : neighbours[0], out);
        // Further axes: where the first left the cell unchanged, the next one's result (equal to
        // the centre unless that axis fired; a fired cell whose mean equals the centre is the
        // same either way).
        const std::size_t size = other_axis_.size();
        for (std::size_t axis = 1; axis < neighbours.size(); ++axis) {
            run(centre, neighbours[axis], other_axis_.data());
            for (std::size_t p = 0; p < size; ++p) {
                if (out[p] == centre[p]) {
                    out[p] = other_axis_[p];
                }
            }
        }
    }

  private:
    void run(const CostValue* centre, const NeighbourPlanes& axis, CostValue* out) {
        const int width = width_;  // locals, for vectorisation
        const int height = height_;
        std::int32_t* __restrict columns = column_sum_.data() + 1;  // [-1] and [width] stay 0
        for (int y = 0; y < height; ++y) {
            const std::size_t offset = static_cast<std::size_t>(y) * width;
            const CostValue* __restrict c = centre + offset;
            for (int x = 0; x < width; ++x) {
                columns[x] = c[x];
            }
            if (y > 0) {
                const CostValue* __restrict up = c - width;
                for (int x = 0; x < width; ++x) {
                    columns[x] += up[x];
                }
            }
            if (y + 1 < height) {
                const CostValue* __restrict down = c + width;
                for (int x = 0; x < width; ++x) {
                    columns[x] += down[x];
                }
            }
            const CostValue* __restrict b = axis.before != nullptr ? axis.before + offset : nullptr;
            const CostValue* __restrict a = axis.after != nullptr ? axis.after + offset : nullptr;
            CostValue* __restrict dst = out + offset;
            for (int x = 0; x < width; ++x) {
                const int value = c[x];
                // A missing neighbour is given a difference of 2 * value, which never agrees.
                const int diff_before = b != nullptr ? b[x] - value : 2 * value;
                const int diff_after = a != nullptr ? a[x] - value : 2 * value;
                const bool fire =
                    fx::agrees(value + diff_before, value) || fx::agrees(value + diff_after, value);
                const auto box =
                    static_cast<std::uint32_t>(columns[x - 1] + columns[x] + columns[x + 1]);
                dst[x] =
                    fire ? static_cast<CostValue>(fx::mean9(box)) : static_cast<CostValue>(value);
            }
        }
    }

    int width_;
    int height_;
    std::vector<std::int32_t> column_sum_;  // 3-row sums of one row, one zero each side
    std::vector<CostValue> other_axis_;
};

}  // namespace

std::unique_ptr<Refiner> make_ca_rule1(int width, int height) {
    return std::make_unique<CaRule1>(width, height);
}

}  // namespace stereo
