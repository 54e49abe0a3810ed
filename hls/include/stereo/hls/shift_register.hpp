// A delay line held as an array (RTL: a chain of registers): one step moves every element one
// place on and takes the entering value at element 0, so element i is what entered i + 1 steps
// before the newest. A synthesis tool maps the loop to a shift register when the array is
// partitioned (ARRAY_PARTITION complete).
#pragma once

namespace stereo::hls {

template <typename T, int N>
void shift_in(T (&line)[N], const T& entering) {
#pragma HLS INLINE
    for (int i = N - 1; i > 0; --i) {
        line[i] = line[i - 1];
    }
    line[0] = entering;
}

}  // namespace stereo::hls
