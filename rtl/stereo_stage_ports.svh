// The ports every DSI stage module begins its port list with (docs/rtl.md, "The stage
// contract"): the clock, the coordinate reset, the pixel step, the group of labels this clock
// works on, and the coordinates of the pixel the input data belongs to. Included inside the port
// lists of stereo_cost, stereo_aggregate, stereo_window3x3, stereo_ca_plane and stereo_wta, which
// declare the parameters NDISP and LANES it uses.
    input  wire logic           clk,
    input  wire logic           rst,  // clears coordinates only
    input  wire logic           ce,   // the pixel step (at group G-1, G = NDISP / LANES)
    /* verilator lint_off UNUSEDSIGNAL */  // LANES = NDISP: always 0
    input  wire logic [((NDISP / LANES > 1) ? $clog2(NDISP / LANES) : 1)-1:0] group,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire fx_pkg::coord_t in_x,
    input  wire fx_pkg::coord_t in_y,
