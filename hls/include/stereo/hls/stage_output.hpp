// The output registers every stage ends with (RTL: rtl/stereo_coord_reg.sv and the data
// register beside it): the coordinates of the pixel leaving, set to "no pixel" by reset, and for
// the stages that pass disparity lanes on, its LANES values (no reset, as in the RTL).
#pragma once

#include "stereo/hls/types.hpp"

namespace stereo::hls {

class coord_output {
  public:
    // Clears the coordinates only ("no pixel"), like the RTL's reset; data stays.
    void reset() {
        out_x_ = 0;
        out_y_ = kNoPixel;
    }

    coord_t out_x() const { return out_x_; }
    coord_t out_y() const { return out_y_; }

  protected:
    coord_t out_x_ = 0;
    coord_t out_y_ = kNoPixel;
};

// A pipeline's reset: every stage's reset(), in the order given.
template <typename... Stages>
void reset_stages(Stages&... stages) {
    (stages.reset(), ...);
}

template <typename T, int LANES>
class lane_output : public coord_output {
  public:
    using value_type = T;
    static constexpr int kLanes = LANES;
    using Lanes = T[LANES];

    const Lanes& out_data() const { return out_data_; }

  protected:
    Lanes out_data_ = {};
};

// The winner the selection stage and the ones after it pass along (RTL: out_label, out_border,
// out_cost of stereo_wta and stereo_validate): its label, whether the border rule holds there,
// and its cost.
class winner_output {
  public:
    disparity_t out_label() const { return out_label_; }
    bool out_border() const { return out_border_; }
    agg_t out_cost() const { return out_cost_; }

  protected:
    disparity_t out_label_ = 0;
    bool out_border_ = false;
    agg_t out_cost_ = 0;
};

}  // namespace stereo::hls
