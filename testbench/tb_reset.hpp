// The reset of the small stage testbenches: rst high for two clocks with ce high (reset must win
// over a step), then low with ce low.
#pragma once

namespace stereo::tb {

template <class Harness>
void reset_stage(Harness& harness) {
    auto& model = harness.model();
    model.ce = 1;
    harness.pulse_reset();
    model.ce = 0;
}

}  // namespace stereo::tb
