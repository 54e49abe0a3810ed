// The core's AXI4-Stream ports (docs/rtl.md, "Stream interface"): the pixel pair in, the
// disparity beat out; tuser marks the first beat of a frame, tlast the last of a row. Included
// at the end of the port lists of stereo_top and of the wrappers that expose its streams
// (stereo_synth_top, stereo_axil_top), so the three declare them once.
    input  wire logic [fx_pkg::IN_BEAT_BITS-1:0] s_axis_tdata,  // {right RGB, left RGB}
    input  wire logic                            s_axis_tvalid,
    output      logic                            s_axis_tready,
    input  wire logic                            s_axis_tlast,
    input  wire logic                            s_axis_tuser,
    output      fx_pkg::out_beat_t               m_axis_tdata,
    output      logic                            m_axis_tvalid,
    input  wire logic                            m_axis_tready,
    output      logic                            m_axis_tlast,
    output      logic                            m_axis_tuser
