#!/usr/bin/env python3
"""check_xdc_ports.py RTL MODULE XDC: every port of MODULE (in the SystemVerilog file RTL) has a
PACKAGE_PIN and an IOSTANDARD in the Vivado constraints XDC, the XDC names no other port, no two
ports share a pin, and the port named `clk` has a create_clock. Buses are checked bit by bit
(`led[3:0]` needs led[0] .. led[3]). Prints one line per problem and exits 1; exit 0 and a summary
line when the constraints are complete. Used by the ctest board.arty_xdc_constrains_every_port."""
import re
import sys


def module_ports(text, module):
    """The port bits of MODULE: {name or name[i]}."""
    text = re.sub(r"//[^\n]*|/\*.*?\*/", " ", text, flags=re.S)
    start = re.search(r"\bmodule\s+%s\b" % re.escape(module), text)
    if not start:
        sys.exit("check_xdc_ports.py: error: no module %s" % module)
    body = text[start.end():text.index(");", start.end())]
    # The port list follows the parameter list #( ... ).
    if body.lstrip().startswith("#"):
        depth, i = 0, body.index("(")
        for i in range(body.index("("), len(body)):
            depth += {"(": 1, ")": -1}.get(body[i], 0)
            if depth == 0:
                break
        body = body[i + 1:]
    ports = set()
    pattern = r"\b(?:input|output|inout)\b\s*(?:wire\s+)?(?:logic\s*)?(\[(\d+)\s*:\s*(\d+)\]\s*)?(\w+)"
    for match in re.finditer(pattern, body):
        name = match.group(4)
        if match.group(1):
            high, low = int(match.group(2)), int(match.group(3))
            for bit in range(min(high, low), max(high, low) + 1):
                ports.add("%s[%d]" % (name, bit))
        else:
            ports.add(name)
    return ports


def xdc_constraints(text):
    """{port: {property: value}} from set_property lines, and the ports with a create_clock."""
    props, clocks = {}, set()
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        ports = re.search(r"\[get_ports\s+(\{[^}]*\}|\S+?)\]", line)
        if not ports:
            continue
        names = ports.group(1).strip("{}").split()
        if line.startswith("create_clock"):
            clocks.update(names)
            continue
        if not line.startswith("set_property"):
            continue
        pairs = re.search(r"-dict\s+\{([^}]*)\}", line)
        if pairs:
            words = pairs.group(1).split()
            values = dict(zip(words[0::2], words[1::2]))
        else:
            words = line.split()
            values = {words[1]: words[2]}
        for name in names:
            props.setdefault(name, {}).update(values)
    return props, clocks


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: check_xdc_ports.py RTL MODULE XDC")
    rtl, module, xdc = sys.argv[1:]
    ports = module_ports(open(rtl).read(), module)
    props, clocks = xdc_constraints(open(xdc).read())
    problems = []
    for port in sorted(ports):
        values = props.get(port, {})
        for required in ("PACKAGE_PIN", "IOSTANDARD"):
            if required not in values:
                problems.append("%s: no %s" % (port, required))
    for name in sorted(set(props) - ports):
        problems.append("%s: constrained, but %s has no such port" % (name, module))
    pins = {}
    for port, values in props.items():
        pin = values.get("PACKAGE_PIN")
        if pin and pin in pins:
            problems.append("%s and %s share pin %s" % (pins[pin], port, pin))
        pins.setdefault(pin, port)
    if "clk" in ports and "clk" not in clocks:
        problems.append("clk: no create_clock")
    for problem in problems:
        print("check_xdc_ports.py: %s" % problem)
    if problems:
        return 1
    print("check_xdc_ports.py: all %d port bits of %s constrained in %s" % (len(ports), module, xdc))
    return 0


if __name__ == "__main__":
    sys.exit(main())
