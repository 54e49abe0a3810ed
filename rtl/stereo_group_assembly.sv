// stereo_group_assembly: the output register of a time-multiplexed stage (docs/rtl.md,
// "Time-multiplexed lanes"), which computes one group of LANES labels per clock but hands all
// NDISP labels of a pixel to the next stage at the step.
//
// At the clocks of groups 0 .. G-2 (`group` below G-1) the group's result is shifted into an
// assembly register of G-1 groups (group 0 lowest after G-1 shifts); at the step (ce, which comes
// at group G-1) out_data takes the assembly register and the last group's result. G = 1 (the
// all-parallel stage): out_data is a plain register stepped with ce.
`default_nettype none

module stereo_group_assembly #(
    parameter int GROUP_BITS = 8,  // one group's result (LANES labels)
    parameter int GROUPS     = 2   // label groups per pixel step
) (
    input  wire logic                           clk,
    input  wire logic                           ce,  // the pixel step (at group G-1)
    /* verilator lint_off UNUSEDSIGNAL */  // G = 1: always 0
    input  wire logic [((GROUPS > 1) ? $clog2(GROUPS) : 1)-1:0] group,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire logic [GROUP_BITS-1:0]          in_group,  // this clock's group result
    output      logic [GROUPS*GROUP_BITS-1:0]   out_data   // all groups, group 0 lowest
);
  generate
    if (GROUPS > 1) begin : g_assemble
      logic [(GROUPS-1)*GROUP_BITS-1:0] assembled;
      logic collecting;  // a group below the last
      assign collecting = 32'(group) != GROUPS - 1;
      if (GROUPS > 2) begin : g_shift
        always_ff @(posedge clk) begin
          if (collecting) assembled <= {in_group, assembled[(GROUPS-1)*GROUP_BITS-1:GROUP_BITS]};
        end
      end else begin : g_one
        always_ff @(posedge clk) begin
          if (collecting) assembled <= in_group;
        end
      end
      always_ff @(posedge clk) begin
        if (ce) out_data <= {in_group, assembled};
      end
    end else begin : g_parallel
      always_ff @(posedge clk) begin
        if (ce) out_data <= in_group;
      end
    end
  endgenerate
endmodule

`default_nettype wire
