// The hierarchical pass's output stream (docs/hierarchical.md, "The streaming core"): tdata =
// {v[7:0], fx_pkg::out_beat_t}, the vertical offset of a valid pixel's match (0 where invalid)
// above stage 6's beat; tuser on a frame's first pixel, tlast at each row end. Included at the
// end of the port lists of stereo_field_border and stereo_hier_pass.
    output      logic [fx_pkg::OUT_BEAT_BITS+7:0]   m_axis_tdata,
    output      logic                               m_axis_tvalid,
    input  wire logic                               m_axis_tready,
    output      logic                               m_axis_tlast,
    output      logic                               m_axis_tuser
