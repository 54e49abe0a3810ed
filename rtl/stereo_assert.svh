// `STEREO_ASSERT(NAME, CONDITION, MESSAGE): the parameter check of every module (docs/rtl.md,
// "Parameter checks"). Written in a module body (a generate item, not inside a process), with
// CONDITION a constant expression of the parameters and MESSAGE a string saying what must hold:
//   `STEREO_ASSERT(lanes_divide_ndisp, LANES >= 1 && NDISP % LANES == 0, "LANES must divide NDISP")
// When CONDITION is false, elaboration stops with
//   NAME failed: (CONDITION): MESSAGE
// and the instance: NAME labels the check's generate block (unique within its module).
//   - with Verilator, $fatal at elaboration, reported with the instance ("... In instance
//     stereo_top.cost"); it is %Warning-USERFATAL, so a run with -Wno-fatal goes on, and the
//     model then stops at the start of simulation with the same message after the instance
//     path (%m, e.g. TOP.stereo_top.cost.lanes_divide_ndisp);
//   - with Yosys (read_verilog defines YOSYS), $error at elaboration with file and line. Yosys
//     0.23 has no elaboration-time $fatal and prints $error's first argument as it is (no
//     format), so the message is one concatenated string there.
// A check that holds generates nothing: the synthesised netlist is the same with or without it.
`ifndef STEREO_ASSERT_SVH
`define STEREO_ASSERT_SVH

`ifdef YOSYS
`define STEREO_ASSERT(name, condition, message) \
  if (!(condition)) begin : name \
    $error({`"name`", " failed: (", `"condition`", "): ", message}); \
  end
`else
`define STEREO_ASSERT(name, condition, message) \
  if (!(condition)) begin : name \
    $fatal(1, "%s failed: (%s): %s", `"name`", `"condition`", message); \
    initial $fatal(1, "%m failed: (%s): %s", `"condition`", message); \
  end
`endif

`endif  // STEREO_ASSERT_SVH
