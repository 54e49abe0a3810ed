# Example constraints for stereo_axil_top on a Digilent Arty A7-100T (XC7A100T-1CSG324C) when the
# core is the top of a test build: the board's 100 MHz oscillator drives clk. In a real system the AXI4-Lite and AXI4-Stream ports connect
# to a processor and a video DMA inside the FPGA (docs/integration.md), and only the clock
# constraint below is needed, on the clock that block design gives the core.
#
# Pins from the board's reference manual: CLK100MHZ = E3, ck_rst (RESET button) = C2.

set_property -dict {PACKAGE_PIN E3 IOSTANDARD LVCMOS33} [get_ports clk]
create_clock -name sys_clk -period 10.000 -waveform {0.000 5.000} [get_ports clk]

# The reset button ck_rst (pin C2) is active low and rst is active high: in a board top that
# instantiates stereo_axil_top with `.rst(~ck_rst)`, add
#   set_property -dict {PACKAGE_PIN C2 IOSTANDARD LVCMOS33} [get_ports ck_rst]
#   set_false_path -from [get_ports ck_rst]

set_property CFGBVS VCCO [current_design]
set_property CONFIG_VOLTAGE 3.3 [current_design]
