# Vitis HLS flow for the stereo pipeline's synthesisable top, hls/stereo_hls_synth_top.cpp
# (640x480 frames, 64 disparity lanes, 11x11 window): C simulation, C synthesis and C/RTL
# co-simulation, each behind a switch. Untested here: Vitis HLS is not installed in this
# repository's environment (only the g++ C simulation has been run, see README.md "HLS").
#
#   vitis_hls -f scripts/hls/run_vitis_hls.tcl -tclargs [key=value ...]
#
# Options (defaults in brackets):
#   csim=0|1       C simulation with hls/tb_stereo_hls.cpp                      [1]
#   csynth=0|1     C synthesis                                                  [1]
#   cosim=0|1      C/RTL co-simulation (needs csynth; the testbench runs with   [0]
#                  --quick, the 200x120 frame only)
#   export=0|1     export the IP (ip_catalog)                                   [0]
#   part=NAME      FPGA part                                        [xczu7ev-ffvc1156-2-e]
#   clock=NS       clock period in ns                                           [5]
#   project=DIR    project folder                                 [build-vitis/stereo_hls]
#   solution=NAME  solution name                       [<part family>_<clock>ns, e.g. xczu7ev_5ns]
#   seed=N         testbench seed                                               [2010]
#   root=DIR       repository root                     [two folders above this script]
#
# Example: vitis_hls -f scripts/hls/run_vitis_hls.tcl -tclargs csim=1 csynth=0

set options [dict create \
    csim 1 csynth 1 cosim 0 export 0 \
    part xczu7ev-ffvc1156-2-e clock 5 \
    project build-vitis/stereo_hls solution "" seed 2010 \
    root [file normalize [file join [file dirname [info script]] .. ..]]]

if {[info exists ::argv]} {
    foreach argument $::argv {
        if {![regexp {^([a-z]+)=(.*)$} $argument -> key value]} {
            error "expected key=value, got '$argument'"
        }
        if {![dict exists $options $key]} {
            error "unknown option '$key' (known: [dict keys $options])"
        }
        dict set options $key $value
    }
}
dict with options {}
if {$solution eq ""} {
    set solution "[lindex [split $part -] 0]_${clock}ns"
}
puts "run_vitis_hls: csim=$csim csynth=$csynth cosim=$cosim export=$export part=$part\
      clock=${clock}ns project=$project solution=$solution"

# The kernels are C++17 and header-only (hls/include); the constants come from the model's
# header. The testbench compiles the golden model in, which is C++20.
set design_flags "-std=c++17 -I$root/hls/include -I$root/model/include -I$root/hls"
set tb_flags "-std=c++20 -I$root/hls/include -I$root/model/include -I$root/hls"

# A new C synthesis starts from a clean project and solution; without one (csim or cosim only)
# the existing solution, and the RTL of its last synthesis, are kept.
set reset [expr {$csynth ? "-reset" : ""}]

open_project {*}$reset $project
set_top stereo_hls_synth_top
add_files $root/hls/stereo_hls_synth_top.cpp -cflags $design_flags
add_files -tb $root/hls/tb_stereo_hls.cpp -cflags $tb_flags
foreach model_source {pipeline.cpp kernel.cpp search.cpp edge_frontend.cpp stages/costs.cpp
                      stages/cost_ad.cpp stages/cost_truncated_ad.cpp stages/census.cpp
                      stages/aggregate_gaussian.cpp stages/ca_rule1.cpp stages/ca_rule2.cpp
                      stages/wta.cpp} {
    add_files -tb $root/model/src/$model_source -cflags "$tb_flags -I$root/model/src"
}

open_solution {*}$reset $solution -flow_target vivado
set_part $part
create_clock -period $clock -name default

if {$csim} {
    csim_design -argv $seed
}
if {$csynth} {
    csynth_design
}
if {$cosim} {
    if {!$csynth} {
        puts "run_vitis_hls: cosim uses the RTL of the last csynth of $project/$solution"
    }
    cosim_design -argv "--quick $seed"
}
if {$export} {
    export_design -format ip_catalog
}
exit
