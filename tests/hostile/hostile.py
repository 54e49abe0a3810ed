#!/usr/bin/env python3
"""The project's hostile suite (issue 51; docs/reliability.md, "The hostile suite").

Generates cases instead of listing them: for every command of `stereo`, its options as its own
--help lists them, each at hostile values of its type (boundaries, inf, nan, huge, empty, words,
octal- and hex-looking integers, device and folder paths, non-UTF-8 and over-long names); every
output option pointed at every file the command reads (the files inside input folders included);
random combinations of those; truncated and bit-flipped image files as inputs; and the
environment turned against the command (stdout on /dev/full or closed, a file-size limit,
SIGTERM/SIGINT/SIGHUP at random moments during a write). Every case is checked against one
contract, the one docs/reliability.md promises:

  * the process ends by itself (no signal but the one a case sends, no hang past --timeout);
  * its exit code is 0, 1, 2 or 3; a failure prints nothing on stdout and exactly one stderr line
    "stereo: error: ..." and creates or changes no file;
  * no file it reads changes, whatever the outcome, and no temporary file survives it;
  * its peak memory stays under --max-rss-mb.

    hostile.py STEREO FIXTURES SLAM_FIXTURES WORK [--cases N] [--seed S] [--jobs J]

FIXTURES and SLAM_FIXTURES are make_cli_fixtures' and make_slam_fixtures' folders; they are
copied into WORK first, so a case that broke the contract cannot spoil another test's fixtures.
--cases N draws N cases (seeded, the same N cases for the same seed) from all the generated ones;
0 runs all of them. Exit 0 when no case broke the contract, 1 otherwise (each break printed with
the command to reproduce it).
"""

import argparse
import concurrent.futures
import hashlib
import os
import random
import re
import resource
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time

# Hidden temporaries the output layer creates beside a destination: ".NAME.XXXXXX[.EXT]".
TEMPORARY = re.compile(r"^\..+\.[A-Za-z0-9]{6}(\.[A-Za-z0-9]+)?$")
ERROR_LINE = re.compile(rb"^stereo: error: [^\n]+\n$")

# ---- the commands: one working invocation each, and which of its options name outputs -------
# @I@ is the copy of the image fixtures, @S@ of the SLAM sequences, @O@ the folder of outputs.
BASES = {
    "match": ["match", "@I@/left.png", "@I@/right.png", "-o", "@O@/match.png", "--ndisp", "8"],
    "eval": ["eval", "@I@/gt.png", "@I@/gt.png"],
    "middlebury": ["middlebury", "--data", "@I@"],
    "cosim": ["cosim", "@I@/left.png", "@I@/right.png", "--ndisp", "8"],
    "fis": ["fis", "--left", "0.2", "--center", "0.5", "--right", "0.1"],
    "avoid": ["avoid", "@I@/left.png", "@I@/right.png", "--ndisp", "8", "--threshold", "2"],
    "distort": ["distort", "@I@/scene", "@O@/distorted"],
    "relight": ["relight", "@I@/left.png", "@O@/relit.png"],
    "slam": ["slam", "@S@/ok", "--ndisp", "16", "--window", "5"],
    "quad": ["quad", "@I@/left.png", "@I@/right.png", "@I@/left.png", "@I@/right.png", "-o",
             "@O@/quad.pfm", "--ndisp", "8", "--window", "5"],
    "cloud": ["cloud", "@I@/gt.png", "@I@/left.png", "-o", "@O@/cloud.ply", "--focal", "100",
              "--baseline", "0.1"],
    "board": ["board", "@I@/left.png", "@I@/right.png", "--port", "/dev/null", "--timeout", "50"],
}
# The options that name a file the command writes, with an extension it accepts.
OUTPUTS = {
    "match": {"-o": ".png", "--color": ".png", "--certainty": ".png", "--reasons": ".png"},
    "eval": {"--error-map": ".png"},
    "middlebury": {"--markdown": ".md", "--json": ".json"},
    "cosim": {"-o": ".png", "--diff": ".png"},
    "avoid": {"--overlay": ".png"},
    "slam": {"--map": ".png", "--trajectory": ".txt", "--vdisparity": ".png"},
    "quad": {"-o": ".pfm", "--certainty": ".png", "--source": ".png"},
    "cloud": {"-o": ".ply"},
    "board": {"-o": ".png"},
    "relight": {},
    "distort": {},
    "fis": {},
}
# Files inside the input folders, as outputs must never replace them.
INSIDE = {
    "slam": ["@S@/ok/image_l/000000.png", "@S@/ok/image_r/000002.png", "@S@/ok/calib.txt",
             "@S@/ok/poses.txt", "@S@/ok"],
    "distort": ["@I@/scene/left.png", "@I@/scene/right.png", "@I@/scene"],
    "middlebury": ["@I@/left.png"],
}
# The files each base reads, as patterns under its inputs (a folder input reads what is inside).
READS = {
    "match": ["@I@/left.png", "@I@/right.png"],
    "eval": ["@I@/gt.png"],
    "cosim": ["@I@/left.png", "@I@/right.png"],
    "avoid": ["@I@/left.png", "@I@/right.png"],
    "relight": ["@I@/left.png"],
    "slam": ["@S@/ok/**"],
    "quad": ["@I@/left.png", "@I@/right.png"],
    "cloud": ["@I@/gt.png", "@I@/left.png"],
    "board": ["@I@/left.png", "@I@/right.png"],
    "distort": ["@I@/scene/**"],
    "middlebury": [],
    "fis": [],
}

INTEGERS = ["-1", "0", "1", "2", "3", "7", "064", "0x10", "1e3", "8.5", "2147483647", "2147483648",
            "-2147483649", "99999999999999999999", "", "abc", "+8", "--", "１２"]
REALS = ["nan", "inf", "-inf", "1e308", "-1e308", "1e-320", "0", "-0", "-1", "1", "0.5", "1e6",
         "", "abc", "0x1p3", "1e400", "  2"]
PATHS = ["", "/dev/null", "/dev/full", "/dev/zero", "@I@", "@I@/fifo.png", "@O@/missing/x.png",
         "@I@/left.png", "@O@/\udcff\udcfe.png", "@O@/" + "n" * 250 + ".png", "@O@/x.unknownext",
         "@O@/.hidden.png", "@O@/link.png", "-o", "@I@/not_an_image.png", "/proc/self/mem"]


def help_options(stereo, command):
    """The options of `stereo COMMAND --help`: (names, type) with type INT, UINT, FLOAT, TEXT or
    FLAG, the first name as the one to use."""
    text = subprocess.run([stereo, command, "--help"], capture_output=True, text=True,
                          check=False).stdout
    options = []
    for line in text.splitlines():
        match = re.match(r"^  (-[-\w,]+)(?: ([A-Z]+))?", line)
        if not match or match.group(1) in ("-h,--help",):
            continue
        names = match.group(1).split(",")
        kind = match.group(2) or "FLAG"
        if kind not in ("INT", "UINT", "FLOAT", "TEXT"):
            kind = "FLAG"
        options.append((names[-1] if names[-1].startswith("--") else names[0], kind))
    return options


def generate(stereo, seed):
    """Every case: (kind, command, argv template, extra) where extra sets the environment."""
    cases = []
    options = {command: help_options(stereo, command) for command in BASES}
    for command, base in BASES.items():
        for name, kind in options[command]:
            values = {"INT": INTEGERS, "UINT": INTEGERS, "FLOAT": REALS, "TEXT": PATHS}.get(kind)
            if values is None:
                cases.append(("flag", command, base + [name], {}))
                continue
            for value in values:
                cases.append(("value", command, base + [name, value], {}))
            cases.append(("missing-value", command, base + [name], {}))
            cases.append(("twice", command, base + [name, values[0], name, values[1]], {}))
        # Every output option at every file the command reads.
        for option, _ in OUTPUTS[command].items():
            targets = [t for t in READS[command] if not t.endswith("/**")]
            for target in targets + INSIDE.get(command, []) + ["@I@/gt.png", "@I@/left.png"]:
                cases.append(("output-over-input", command, without(base, option) +
                              [option, target], {"over": target}))
        # The environment.
        cases.append(("stdout-full", command, base + json_flag(options[command]), {"stdout": "full"}))
        cases.append(("stdout-closed", command, base + json_flag(options[command]),
                      {"stdout": "closed"}))
        for limit in (1, 7, 64):
            cases.append(("file-size-limit", command, base, {"fsize": limit * 512}))
        for signum in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
            for delay in (0.01, 0.05, 0.2):
                cases.append(("signal", command, base, {"signal": signum, "delay": delay}))
    # Signals while a large output is being written (@B@: a 3000 x 2000 noise image, whose PNG
    # takes a second to encode), at delays drawn over the whole run.
    delays = random.Random(seed + 1)
    large = [["relight", "@B@/big.ppm", "@O@/relit.png"],
             ["match", "@B@/big.ppm", "@B@/big.ppm", "--ndisp", "4", "--window", "3", "--no-ca",
              "-o", "@O@/match.png", "--color", "@O@/color.png"],
             # The waveform is written during the whole run (io::StagedOutput).
             ["cosim", "@I@/left.png", "@I@/right.png", "--ndisp", "8", "--frames", "4",
              "--trace", "@O@/wave.fst"]]
    for argv in large:
        for signum in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP, signal.SIGQUIT):
            for _ in range(10):
                # A fraction of the run's undisturbed duration: most of the run is decoding and
                # matching, so the draws lean towards its end, where the outputs are written.
                cases.append(("signal-large", argv[0], argv,
                              {"signal": signum, "fraction": round(delays.uniform(0.5, 1.05), 3)}))
        for limit in (1 << 20, 5 << 20):
            cases.append(("file-size-limit-large", argv[0], argv, {"fsize": limit}))
    # Corrupt images as the left input of the image commands.
    for command in ("match", "avoid", "relight", "cosim", "eval"):
        for mode in ("truncate", "flip"):
            for n in range(12):
                cases.append(("corrupt-input", command, BASES[command],
                              {"corrupt": mode, "index": n}))
    # Random combinations: two to four hostile options at once.
    rng = random.Random(seed)
    for command, base in BASES.items():
        typed = [o for o in options[command] if o[1] != "FLAG"]
        for _ in range(60):
            argv = list(base)
            for name, kind in rng.sample(typed, min(len(typed), rng.randint(2, 4))):
                pool = {"INT": INTEGERS, "UINT": INTEGERS, "FLOAT": REALS}.get(kind, PATHS)
                argv += [name, rng.choice(pool)]
            cases.append(("combination", command, argv, {}))
    return cases


def write_noise_ppm(path, width, height, seed):
    """A binary PPM of smooth noise (compresses a little, so PNG encoding takes its time)."""
    rng = random.Random(seed)
    row = bytes(rng.randrange(256) for _ in range(width * 3))
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (width, height))
        for y in range(height):
            shift = (y * 7) % len(row)
            f.write(row[shift:] + row[:shift])


def without(argv, option):
    """argv without `option` and its value."""
    out, skip = [], False
    for i, word in enumerate(argv):
        if skip:
            skip = False
            continue
        if word == option:
            skip = True
            continue
        out.append(word)
    return out


def json_flag(options):
    return ["--json"] if ("--json", "FLAG") in options else []


# ---- one case ------------------------------------------------------------------------------
class Sandbox:
    """A fresh copy of the fixtures for one case: inputs, outputs, and their snapshot."""

    def __init__(self, root, fixtures, slam_fixtures, with_sequences=True):
        self.large = os.path.join(root, "large")  # shared, read-only
        self.root = tempfile.mkdtemp(dir=root)
        self.inputs = os.path.join(self.root, "in")
        self.slam = os.path.join(self.root, "seq")
        self.out = os.path.join(self.root, "out")
        copy_tree(fixtures, self.inputs)
        os.makedirs(self.slam)
        if with_sequences:  # only the cases that name one: the copy is most of a case's setup
            copy_tree(slam_fixtures, self.slam)
        scene = os.path.join(self.inputs, "scene")
        os.makedirs(scene)
        for name, source in (("left.png", "scene_left.png"), ("right.png", "scene_right.png")):
            shutil.copy(os.path.join(self.inputs, source), os.path.join(scene, name))
        os.makedirs(self.out)
        # A previous output in place of every output a base writes, so that "kept" is checked.
        for name in ("match.png", "relit.png", "quad.pfm", "cloud.ply", "link.png"):
            with open(os.path.join(self.out, name), "wb") as previous:
                previous.write(b"previous " + name.encode())

    def expand(self, word):
        return (word.replace("@I@", self.inputs).replace("@S@", self.slam)
                .replace("@O@", self.out).replace("@B@", self.large))

    def snapshot(self):
        state = {}
        for top in (self.inputs, self.slam, self.out):
            for folder, _, files in os.walk(top):
                for name in files:
                    path = os.path.join(folder, name)
                    mode = os.lstat(path).st_mode
                    if stat.S_ISREG(mode):
                        with open(path, "rb") as f:
                            state[path] = hashlib.sha256(f.read()).hexdigest()
                    else:
                        state[path] = "special"
        return state

    def reads(self, command, template):
        """The files the case's command reads: its base's inputs (every file inside an input
        folder) and any fixture file the case names as an input."""
        paths = set()
        for pattern in READS[command]:
            expanded = self.expand(pattern)
            if expanded.endswith("/**"):
                for folder, _, files in os.walk(expanded[:-3]):
                    paths.update(os.path.join(folder, f) for f in files)
            else:
                paths.add(expanded)
        return paths

    def remove(self):
        shutil.rmtree(self.root, ignore_errors=True)


def copy_tree(source, destination):
    os.makedirs(destination, exist_ok=True)
    for name in os.listdir(source):
        path = os.path.join(source, name)
        target = os.path.join(destination, name)
        mode = os.lstat(path).st_mode
        if stat.S_ISFIFO(mode):
            os.mkfifo(target)
        elif stat.S_ISDIR(mode):
            copy_tree(path, target)
        elif stat.S_ISREG(mode):
            shutil.copy(path, target)
    os.chmod(os.path.join(destination, "unreadable.png"), 0) if os.path.exists(
        os.path.join(destination, "unreadable.png")) else None


def corrupt(path, mode, index, rng):
    data = bytearray(open(path, "rb").read())
    if mode == "truncate":
        data = data[: rng.randint(0, len(data) - 1)]
    else:
        for _ in range(1 + index % 4):
            position = rng.randrange(len(data))
            data[position] ^= 1 << rng.randrange(8)
    with open(path, "wb") as f:
        f.write(data)


def run_case(case, args):
    kind, command, template, extra = case
    box = Sandbox(args.work, args.fixtures, args.slam_fixtures,
                  any("@S@" in word for word in template))
    try:
        return check_case(box, case, args)
    finally:
        box.remove()


def check_case(box, case, args):
    kind, command, template, extra = case
    argv = [args.stereo] + [box.expand(w) for w in template]
    rng = random.Random(hashlib.sha256(repr(case).encode()).hexdigest())
    if kind == "corrupt-input":
        target = os.path.join(box.inputs, "gt.png" if command == "eval" else "left.png")
        corrupt(target, extra["corrupt"], extra["index"], rng)
    if kind == "value" and template[-1] == "@O@/link.png":
        os.remove(os.path.join(box.out, "link.png"))
        os.symlink(os.path.join(box.inputs, "left.png"), os.path.join(box.out, "link.png"))
    before = box.snapshot()
    stdout_path = os.path.join(box.root, "stdout")
    stderr_path = os.path.join(box.root, "stderr")
    env = dict(os.environ, STEREO_VERILATOR=args.no_verilator, STEREO_COSIM_CACHE=box.root)

    def limits():
        resource.setrlimit(resource.RLIMIT_AS, (args.max_as_mb << 20, args.max_as_mb << 20))
        if "fsize" in extra:
            resource.setrlimit(resource.RLIMIT_FSIZE, (extra["fsize"], extra["fsize"]))
        if extra.get("stdout") == "closed":
            os.close(1)

    with open(stderr_path, "wb") as err:
        if extra.get("stdout") == "full":
            out = open("/dev/full", "wb")
        elif extra.get("stdout") == "closed":
            out = None
        else:
            out = open(stdout_path, "wb")
        started = time.monotonic()
        process = subprocess.Popen(
            argv, stdin=subprocess.DEVNULL, stdout=out if out is not None else subprocess.DEVNULL,
            stderr=err, env=env, preexec_fn=limits, cwd=box.root,
            pass_fds=(), close_fds=True)
        sent = None
        finished = None
        if "signal" in extra:
            time.sleep(extra["delay"] if "delay" in extra
                       else extra["fraction"] * args.durations[tuple(template)])
            pid, status, usage = os.wait4(process.pid, os.WNOHANG)  # not poll(): it would reap
            if pid != 0:
                finished = (status, usage)
            else:
                os.kill(process.pid, extra["signal"])
                sent = extra["signal"]
        status, usage = finished or wait(process, args.timeout)
        process.returncode = 0  # reaped here, not by Popen
        elapsed = time.monotonic() - started
        if out is not None:
            out.close()
    after = box.snapshot()
    stdout = open(stdout_path, "rb").read() if os.path.exists(stdout_path) else b""
    stderr = open(stderr_path, "rb").read()
    return judge(box, case, argv, status, usage, elapsed, sent, before, after, stdout, stderr,
                 args)


def wait(process, timeout):
    deadline = time.monotonic() + timeout
    while True:
        pid, status, usage = os.wait4(process.pid, os.WNOHANG)
        if pid != 0:
            process.returncode = 0
            return status, usage
        if time.monotonic() > deadline:
            process.kill()
            _, status, usage = os.wait4(process.pid, 0)
            process.returncode = 0
            return "hang", usage
        time.sleep(0.005)


def judge(box, case, argv, status, usage, elapsed, sent, before, after, stdout, stderr, args):
    kind, command, template, extra = case
    breaks = []
    if status == "hang":
        breaks.append(f"hang: still running after {args.timeout} s")
        code = None
    elif os.WIFSIGNALED(status):
        signum = os.WTERMSIG(status)
        if signum != sent:
            breaks.append(f"killed by {signal.Signals(signum).name}")
        code = None
    else:
        code = os.WEXITSTATUS(status)
    if sent is not None and code is not None and code == 0 and os.WIFEXITED(status):
        pass  # finished before the signal arrived, or handled it and finished: fine
    rss_mb = usage.ru_maxrss / 1024
    if rss_mb > args.max_rss_mb:
        breaks.append(f"peak memory {rss_mb:.0f} MB > {args.max_rss_mb} MB")
    if code is not None and code not in (0, 1, 2, 3) and sent is None:
        breaks.append(f"exit code {code}")
    failed = code not in (0, None)
    if failed and sent is None:
        if stdout and extra.get("stdout") is None:
            breaks.append(f"failure with {len(stdout)} bytes on stdout")
        if not ERROR_LINE.match(stderr):
            breaks.append("failure without exactly one 'stereo: error:' line: " +
                          repr(stderr[:300]))
    if sent is not None and os.path.exists(box.out) and code is None:
        pass  # killed: the outputs must be the previous ones or complete (checked below)
    if extra.get("stdout") == "full" and code == 0 and writes_stdout(command, template):
        breaks.append("stdout is /dev/full, yet exit 0")
    if extra.get("fsize") and code == 0 and grew(before, after, extra["fsize"]):
        breaks.append("a file over the file-size limit, yet exit 0")
    # The files the command reads never change; on failure nothing changes or appears anywhere.
    # A report that cannot reach standard output (/dev/full) is reported once the files are
    # written (docs/reliability.md, "Standard output"): those files are whole, so they may stay.
    lost_report = extra.get("stdout") == "full" and b"cannot write the standard output" in stderr
    if lost_report:
        failed = False
    reads = box.reads(command, template)
    for path, digest in before.items():
        if path in after and after[path] == digest:
            continue
        if path in reads:
            breaks.append(f"{'changed' if path in after else 'removed'} {rel(box, path)}, "
                          "which the command reads")
        elif failed and sent is None:
            breaks.append(f"{'changed' if path in after else 'removed'} {rel(box, path)} "
                          "and failed")
    for path in after:
        if path not in before and failed and sent is None:
            breaks.append(f"created {rel(box, path)} and failed")
        if TEMPORARY.match(os.path.basename(path)) and path not in before:
            breaks.append(f"temporary left: {rel(box, path)}")
    return breaks, argv, code, elapsed


def writes_stdout(command, template):
    return command in ("eval", "fis", "match", "avoid", "slam", "cloud", "quad", "relight",
                       "distort") and "--help" not in template


def grew(before, after, limit):
    return any(os.path.getsize(p) >= limit for p in after if os.path.isfile(p)
               and after[p] != before.get(p))


def rel(box, path):
    return os.path.relpath(path, box.root)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("stereo")
    parser.add_argument("fixtures")
    parser.add_argument("slam_fixtures")
    parser.add_argument("work")
    parser.add_argument("--cases", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=51)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--max-rss-mb", type=int, default=1500)
    parser.add_argument("--max-as-mb", type=int, default=8192)
    parser.add_argument("--only", default="", help="run only the cases of this kind")
    args = parser.parse_args()
    for name in ("stereo", "fixtures", "slam_fixtures", "work"):
        setattr(args, name, os.path.abspath(getattr(args, name)))
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    args.no_verilator = os.path.join(args.work, "no-verilator")
    with open(args.no_verilator, "w") as f:
        f.write("#!/bin/sh\necho 'verilator is not available in the hostile suite' >&2\nexit 1\n")
    os.chmod(args.no_verilator, 0o755)
    os.makedirs(os.path.join(args.work, "large"))
    write_noise_ppm(os.path.join(args.work, "large", "big.ppm"), 3000, 2000, args.seed)
    cases = generate(args.stereo, args.seed)
    args.durations = {}
    for case in cases:
        if "fraction" in case[3] and tuple(case[2]) not in args.durations:
            box = Sandbox(args.work, args.fixtures, args.slam_fixtures, False)
            started = time.monotonic()
            subprocess.run([args.stereo] + [box.expand(w) for w in case[2]],
                           capture_output=True, check=False)
            args.durations[tuple(case[2])] = time.monotonic() - started
            box.remove()
    if args.only:
        cases = [c for c in cases if c[0] == args.only]
    total = len(cases)
    if args.cases and args.cases < total:
        cases = random.Random(args.seed).sample(cases, args.cases)
    started = time.monotonic()
    broken = 0
    counts = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for case, (breaks, argv, code, elapsed) in zip(
                cases, pool.map(lambda c: run_case(c, args), cases)):
            counts[case[0]] = counts.get(case[0], 0) + 1
            if breaks:
                broken += 1
                print(f"BREAK [{case[0]}] {' '.join(map(repr_word, argv))}"
                      f"{describe_env(case[3])}: exit {code}: " + "; ".join(breaks))
    print(f"{len(cases)} cases of {total} generated ({', '.join(f'{k} {v}' for k, v in sorted(counts.items()))}), "
          f"{broken} broke the contract, {time.monotonic() - started:.0f} s")
    return 1 if broken else 0


def repr_word(word):
    return word if re.fullmatch(r"[\w@%+=:,./-]+", word) else repr(word)


def describe_env(extra):
    parts = [f"{k}={v}" for k, v in extra.items() if k not in ("over",)]
    return f" [{' '.join(parts)}]" if parts else ""


if __name__ == "__main__":
    sys.exit(main())
