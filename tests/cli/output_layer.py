#!/usr/bin/env python3
"""The output layer's guarantees against the environment (docs/reliability.md, "Outputs lose
nothing"), one ctest each (label cli):

    output_layer.py CASE STEREO EXPERIMENTS FIXTURES SLAM_FIXTURES WORK RTL

CASE is one of
  file_size_limit   every kind of writer under a file-size limit (RLIMIT_FSIZE, `ulimit -f`):
                    exit 1, one error line, the previous file kept, no temporary left;
  signals           SIGTERM, SIGINT and SIGHUP at random moments while an output is being
                    written: no temporary survives, the previous file or the whole new one;
  stdout            standard output on /dev/full, closed, or a pipe nobody reads: exit 1 and one
                    error line, for `stereo` and `stereo_experiments`;
  disk_full         a tmpfs filled to random levels (mounted here; skipped when mount fails):
                    an output is whole or not written, the previous file kept, no temporary left;
  folder_contents   outputs over files inside input folders and list files, and new files inside
                    input folders: exit 2, one error line, nothing changed;
  staging           a link planted at the name the video used to be staged under is not
                    followed, and traces are staged inside a private folder;
  sweep             what a SIGKILL leaves is removed by the next run writing into that folder,
                    and nothing of a live process or another machine.
RTL is 1 when the build has the Verilated RTL (cosim and its traces), else 0. Exit 0 when the
guarantee held, 1 with every break printed, 77 when the case cannot run here.
"""

import hashlib
import os
import random
import shutil
import signal
import stat
import struct
import subprocess
import sys
import time

SKIP = 77
FAILURES = []


def fail(message):
    FAILURES.append(message)
    print("FAIL:", message)


def run(argv, stdout=subprocess.PIPE, fsize=None, cwd=None):
    """Runs argv; returns (exit status, stdout bytes, stderr bytes). A negative status is the
    signal that ended it."""

    def limits():
        if fsize is not None:
            import resource
            resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))

    process = subprocess.run(argv, stdout=stdout, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                             preexec_fn=limits, cwd=cwd, timeout=600, check=False)
    out = process.stdout if isinstance(process.stdout, bytes) else b""
    return process.returncode, out, process.stderr


def one_error_line(stderr, program="stereo"):
    lines = stderr.decode(errors="replace").splitlines()
    return len(lines) == 1 and lines[0].startswith(program + ": error: ") and stderr.endswith(b"\n")


def hidden(folder):
    """The hidden entries of a folder: where temporaries live."""
    return sorted(name for name in os.listdir(folder) if name.startswith("."))


def writing(folder):
    """Whether a write is under way in `folder`: a hidden file with bytes in it, or a hidden
    (staging) folder holding one. The empty file a command makes and removes to check that it
    can write there does not count."""
    for name in hidden(folder):
        path = os.path.join(folder, name)
        try:
            if os.path.isdir(path):
                if any(os.path.getsize(os.path.join(path, inner)) > 0
                       for inner in os.listdir(path)):
                    return True
            elif os.path.getsize(path) > 0:
                return True
        except OSError:
            continue
    return False


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def tree(folder):
    """Every file under folder (links followed to their bytes) with its digest."""
    state = {}
    for root, dirs, files in os.walk(folder):
        for name in files + [d for d in dirs if os.path.islink(os.path.join(root, d))]:
            path = os.path.join(root, name)
            if os.path.isfile(path):
                state[os.path.relpath(path, folder)] = digest(path)
            else:
                state[os.path.relpath(path, folder)] = os.readlink(path) \
                    if os.path.islink(path) else "special"
    return state


def fst_without_date(data):
    """An FST trace's bytes without the header's date (fstapi: 119 bytes at offset 202), the only
    part that differs between two runs."""
    return data[:202] + data[202 + 119:]


def same_output(path, reference):
    with open(path, "rb") as f:
        data = f.read()
    with open(reference, "rb") as f:
        expected = f.read()
    if path.endswith(".fst"):
        return fst_without_date(data) == fst_without_date(expected)
    return data == expected


# ---- the inputs and the writers ------------------------------------------------------------

def write_pgm(path, width, height, seed, shift=0):
    rng = random.Random(seed)
    row_bytes = [bytes(rng.randrange(256) for _ in range(width + shift)) for _ in range(height)]
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (width, height))
        for row in row_bytes:
            f.write(row[shift:shift + width])


def write_pfm(path, width, height, value):
    with open(path, "wb") as f:
        f.write(b"Pf\n%d %d\n-1.0\n" % (width, height))
        f.write(struct.pack("<f", value) * (width * height))


class Setup:
    def __init__(self, args):
        (self.case, self.stereo, self.experiments, self.fixtures, self.slam_fixtures, self.work,
         rtl) = args
        self.rtl = rtl == "1"
        # A tmpfs a killed earlier run left mounted.
        subprocess.run(["umount", os.path.join(self.work, "tmpfs")], capture_output=True,
                       check=False)
        shutil.rmtree(self.work, ignore_errors=True)
        os.makedirs(self.work)
        self.inputs = os.path.join(self.work, "inputs")
        os.makedirs(self.inputs)
        self.f = lambda name: os.path.join(self.fixtures, name)
        self.i = lambda name: os.path.join(self.inputs, name)

    def big_cloud_inputs(self, width, height):
        """A disparity and an image of width x height for `stereo cloud` (every pixel a point)."""
        disparity = self.i("cloud_%dx%d.pfm" % (width, height))
        image = self.i("cloud_%dx%d.pgm" % (width, height))
        if not os.path.exists(disparity):
            write_pfm(disparity, width, height, 12.5)
            write_pgm(image, width, height, 5)
        return disparity, image

    def avoid_list(self, frames):
        path = self.i("avoid_list_%d.txt" % frames)
        with open(path, "w") as f:
            for _ in range(frames):
                f.write("%s %s\n" % (self.f("left.png"), self.f("right.png")))
        return path

    def writers(self, big):
        """The kinds of writer: name -> (argv with OUT for the output folder, output file name).
        `big` makes the outputs larger (a longer write)."""
        w, h = (700, 500) if big else (160, 120)
        disparity, image = self.big_cloud_inputs(w, h)
        writers = {
            # write_file_atomic, one file
            "ply": (["cloud", disparity, image, "-o", "OUT/c.ply", "--focal", "100",
                     "--baseline", "0.1"], "c.ply"),
            # write_files_atomic, several files
            "slam": (["slam", os.path.join(self.slam_fixtures, "ok"), "--ndisp", "16", "--window",
                      "5", "--trajectory", "OUT/t.txt", "--map", "OUT/m.png", "--vdisparity",
                      "OUT/v.png"], "m.png"),
            # the MJPG video (io::mjpeg_avi, written by io::write_file_atomic)
            "avi": (["avoid", self.avoid_list(40 if big else 12), "--ndisp", "8", "--border",
                     "2", "--window", "5", "--threshold", "2", "--overlay", "OUT/o.avi"], "o.avi"),
        }
        if self.rtl:  # Verilator's FST writer through io::StagedOutput
            writers["fst"] = (["cosim", self.f("left.png"), self.f("right.png"), "--ndisp", "8",
                               "--frames", "10" if big else "1", "--trace", "OUT/t.fst"],
                              "t.fst")
        return writers

    def argv(self, template, out):
        return [self.stereo] + [word.replace("OUT", out) for word in template]

    def reference(self, name, template, output):
        """A clean run's output, to compare what a run under stress left."""
        folder = os.path.join(self.work, "reference_" + name)
        os.makedirs(folder, exist_ok=True)
        status, _, stderr = run(self.argv(template, folder), stdout=subprocess.DEVNULL)
        if status != 0:
            raise RuntimeError("reference run of %s failed: %s" % (name, stderr.decode()))
        return os.path.join(folder, output)


def put_previous(folder, output):
    path = os.path.join(folder, output)
    with open(path, "wb") as f:
        f.write(b"the previous " + output.encode())
    return path, digest(path)


# ---- the cases -----------------------------------------------------------------------------

def case_file_size_limit(s):
    for name, (template, output) in s.writers(False).items():
        reference = s.reference(name, template, output)
        limit = os.path.getsize(reference) // 2
        out = os.path.join(s.work, "limit_" + name)
        os.makedirs(out)
        path, previous = put_previous(out, output)
        status, stdout, stderr = run(s.argv(template, out), fsize=limit)
        what = "%s under a %d-byte file-size limit" % (name, limit)
        before = len(FAILURES)
        if status != 1:
            fail("%s: exit %s, expected 1 (%r)" % (what, status, stderr[:200]))
        # `avoid` on a sequence streams its lines before the video is written (docs/cli.md).
        if (stdout and name != "avi") or not one_error_line(stderr):
            fail("%s: stdout %r, stderr %r: not one error line" % (what, stdout[:100], stderr))
        if digest(path) != previous:
            fail("%s: the previous %s changed" % (what, output))
        if hidden(out):
            fail("%s: temporaries left: %s" % (what, hidden(out)))
        if len(FAILURES) == before:
            print("ok: %s: %s" % (what, stderr.decode().strip()))


def case_signals(s):
    rng = random.Random(int(os.environ.get("STEREO_SEED", "51")))
    signals = [signal.SIGTERM, signal.SIGINT, signal.SIGHUP]
    caught = 0
    rounds = 0
    for name, (template, output) in s.writers(True).items():
        if name == "slam":
            continue  # its files are small: the writes take microseconds
        reference = s.reference(name, template, output)
        for attempt in range(6):
            rounds += name != "avi"  # the video's write takes milliseconds: rarely caught
            out = os.path.join(s.work, "signal_%s_%d" % (name, attempt))
            os.makedirs(out)
            path, previous = put_previous(out, output)
            number = signals[attempt % len(signals)]

            def defaults():
                for each in signals:
                    signal.signal(each, signal.SIG_DFL)

            process = subprocess.Popen(s.argv(template, out), stdout=subprocess.DEVNULL,
                                       stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                                       preexec_fn=defaults)
            # The moment a temporary appears the write is under way: signal it a random time
            # later, while it may still be writing.
            deadline = time.monotonic() + 120
            sent = False
            while process.poll() is None and time.monotonic() < deadline:
                if writing(out):
                    time.sleep(rng.uniform(0, 0.02))
                    if process.poll() is None:
                        process.send_signal(number)
                        sent = True
                    break
                time.sleep(0.0005)
            _, stderr = process.communicate(timeout=600)
            status = process.returncode
            what = "%s, %s %s" % (name, signal.Signals(number).name,
                                  "sent during the write" if sent else "not sent (finished first)")
            before = len(FAILURES)
            if status == -number:
                caught += 1
                # Killed before the rename: the previous file; after it: the whole new one.
                if digest(path) != previous and not same_output(path, reference):
                    fail("%s: killed, and %s is neither the previous file nor the whole new one"
                         % (what, output))
            elif status == 0:
                if not same_output(path, reference):
                    fail("%s: exit 0 but %s is not the whole output" % (what, output))
            else:
                fail("%s: exit %s (%r)" % (what, status, stderr[:200]))
            if hidden(out):
                fail("%s: temporaries survived: %s" % (what, hidden(out)))
            if len(FAILURES) == before:
                print("ok: %s: status %d, no temporary left, %s" % (
                    what, status, "the previous file" if digest(path) == previous else
                    "the whole new file"))
    if caught < rounds // 3:
        fail("only %d runs were ended by a signal during a write (%d long writes): the test did "
             "not test" % (caught, rounds))
    print("%d runs ended by a signal during the write (%d long writes, 6 videos)"
          % (caught, rounds))


def case_stdout(s):
    out = os.path.join(s.work, "stdout")
    os.makedirs(out)
    commands = [
        ["fis", "--left", "0.2", "--center", "0.5", "--right", "0.1"],
        ["match", s.f("left.png"), s.f("right.png"), "-o", os.path.join(out, "m.png"),
         "--ndisp", "8", "--json"],
        ["eval", s.f("gt.png"), s.f("gt.png")],
        ["slam", os.path.join(s.slam_fixtures, "ok"), "--ndisp", "16", "--window", "5",
         "--json"],
        ["avoid", s.avoid_list(3), "--ndisp", "8", "--border", "2", "--window", "5",
         "--threshold", "2"],
        ["distort", os.path.join(s.work, "scene_copy"), os.path.join(out, "distorted")],
        ["--help"],
    ]
    os.makedirs(os.path.join(s.work, "scene_copy"))
    for name in ("left.png", "right.png"):
        shutil.copy(s.f("scene_" + name), os.path.join(s.work, "scene_copy", name))
    programs = [(s.stereo, "stereo", argv) for argv in commands]
    programs.append((s.experiments, "stereo_experiments",
                     ["avoid-figures", os.path.join(out)]))
    for program, label, argv in programs:
        for how in ("full", "closed", "broken pipe"):
            if how == "full":
                with open("/dev/full", "wb") as full:
                    status, _, stderr = run([program] + argv, stdout=full)
            elif how == "closed":
                process = subprocess.run([program] + argv, stdin=subprocess.DEVNULL,
                                         stderr=subprocess.PIPE, preexec_fn=lambda: os.close(1),
                                         timeout=600, check=False)
                status, stderr = process.returncode, process.stderr
            else:
                reader, writer = os.pipe()
                os.close(reader)
                status, _, stderr = run([program] + argv, stdout=writer)
                os.close(writer)
            what = "%s %s, stdout %s" % (label, argv[0], how)
            if status != 1:
                fail("%s: exit %s, expected 1 (%r)" % (what, status, stderr[:200]))
            elif not one_error_line(stderr, label) or b"standard output" not in stderr:
                fail("%s: stderr %r, expected one error line about the standard output"
                     % (what, stderr))
            else:
                print("ok: %s: %s" % (what, stderr.decode().strip()))


def mount_tmpfs(folder, size):
    os.makedirs(folder, exist_ok=True)
    result = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=%d" % size, "tmpfs", folder],
                            capture_output=True, check=False)
    return result.returncode == 0


def fill(folder, leave):
    """Fills the file system of `folder` until about `leave` bytes are free."""
    filler = os.path.join(folder, "filler")
    if os.path.exists(filler):
        os.remove(filler)
    free = os.statvfs(folder).f_bavail * os.statvfs(folder).f_frsize
    with open(filler, "wb") as f:
        left = max(0, free - leave)
        chunk = b"\0" * (1 << 20)
        while left > 0:
            try:
                left -= f.write(chunk[:min(left, len(chunk))])
            except OSError:
                break


def case_disk_full(s):
    mount_point = os.path.join(s.work, "tmpfs")
    writers = s.writers(False)
    references = {name: s.reference(name, template, output)
                  for name, (template, output) in writers.items()}
    largest = max(os.path.getsize(path) for path in references.values())
    if not mount_tmpfs(mount_point, 4 * largest + (8 << 20)):
        print("skip: cannot mount a tmpfs here (needs root)")
        return SKIP
    try:
        rng = random.Random(int(os.environ.get("STEREO_SEED", "51")))
        failed = 0
        for name, (template, output) in writers.items():
            size = os.path.getsize(references[name])
            # Free space from none to more than the output needs, random in between.
            levels = [0, size // 8] + [rng.randint(1, 2 * size) for _ in range(5)] + [3 * size]
            for level in levels:
                out = os.path.join(mount_point, "%s_%d" % (name, level))
                os.makedirs(out)
                path, previous = put_previous(out, output)
                fill(mount_point, level)
                status, stdout, stderr = run(s.argv(template, out), stdout=subprocess.DEVNULL)
                what = "%s with about %d bytes free (the output is %d)" % (name, level, size)
                before = len(FAILURES)
                if status == 0:
                    if not same_output(path, references[name]):
                        fail("%s: exit 0 but %s is not whole" % (what, output))
                else:
                    failed += 1
                    if status != 1 or not one_error_line(stderr):
                        fail("%s: exit %s, stderr %r" % (what, status, stderr))
                    if digest(path) != previous:
                        fail("%s: failed, yet the previous %s changed" % (what, output))
                if hidden(out):
                    fail("%s: temporaries left: %s" % (what, hidden(out)))
                if len(FAILURES) == before:
                    print("ok: %s: %s" % (what, "written whole" if status == 0
                                          else stderr.decode().strip()))
                shutil.rmtree(out)
        if failed == 0:
            fail("no run met a full disk: the test did not test")
    finally:
        subprocess.run(["umount", mount_point], check=False)
    return 0


def case_folder_contents(s):
    seq = os.path.join(s.work, "seq")
    shutil.copytree(os.path.join(s.slam_fixtures, "ok"), seq)
    os.symlink(seq, os.path.join(s.work, "seq_link"))
    # A Middlebury data folder made of the fixtures (only Tsukuba present).
    data = os.path.join(s.work, "data")
    scene = os.path.join(data, "middlebury2003", "tsukuba")
    os.makedirs(scene)
    for name, source in (("left.png", "left.png"), ("right.png", "right.png"),
                         ("gt.png", "gt.png"), ("nonocc.png", "mask.png"),
                         ("all.png", "mask.png"), ("disc.png", "mask.png")):
        shutil.copy(s.f(source), os.path.join(scene, name))
    # A distort scene whose right image is a link to a file outside it.
    distort_scene = os.path.join(s.work, "scene")
    elsewhere = os.path.join(s.work, "elsewhere")
    os.makedirs(distort_scene)
    os.makedirs(elsewhere)
    shutil.copy(s.f("scene_left.png"), os.path.join(distort_scene, "left.png"))
    shutil.copy(s.f("scene_right.png"), os.path.join(elsewhere, "right.png"))
    os.symlink(os.path.join(elsewhere, "right.png"), os.path.join(distort_scene, "right.png"))
    # A list file naming frames in another folder.
    frames = os.path.join(s.work, "frames")
    os.makedirs(frames)
    for name in ("l.png", "r.png"):
        shutil.copy(s.f("left.png" if name == "l.png" else "right.png"),
                    os.path.join(frames, name))
    lists = os.path.join(s.work, "lists")
    os.makedirs(lists)
    with open(os.path.join(lists, "frames.txt"), "w") as f:
        f.write("../frames/l.png ../frames/r.png\n")
    views = os.path.join(s.work, "views")
    os.makedirs(views)
    for name in ("a.png", "b.png", "c.png", "d.png"):
        shutil.copy(s.f("left.png"), os.path.join(views, name))
    shutil.copy(s.f("calib.txt"), os.path.join(s.work, "calib.ply"))
    shutil.copy(s.f("mask.png"), os.path.join(s.work, "mask.png"))
    slam = ["slam", seq, "--ndisp", "16", "--window", "5"]
    avoid = ["--ndisp", "8", "--border", "2", "--window", "5", "--threshold", "2"]
    cases = [
        slam + ["--map", os.path.join(seq, "image_l", "000000.png")],
        slam + ["--vdisparity", os.path.join(s.work, "seq_link", "image_r", "000001.png")],
        slam + ["--trajectory", os.path.join(seq, "estimate.txt")],
        slam + ["--map", os.path.join(seq, "maps", "m.png")],
        ["avoid", os.path.join(seq, "image_l"), os.path.join(seq, "image_r")] + avoid +
        ["--overlay", os.path.join(seq, "image_l", "sheet.png")],
        ["avoid", os.path.join(seq, "image_l"), os.path.join(seq, "image_r")] + avoid +
        ["--overlay", os.path.join(seq, "image_r", "000002.png")],
        ["avoid", os.path.join(lists, "frames.txt")] + avoid +
        ["--overlay", os.path.join(frames, "r.png")],
        ["middlebury", "--data", data, "--markdown", os.path.join(scene, "gt.png")],
        ["middlebury", "--data", data, "--json", os.path.join(data, "middlebury2003", "r.json")],
        ["middlebury", "--data", data, "--figures", os.path.join(scene, "figures")],
        ["eval", s.f("gt.png"), s.f("gt.png"), "--nonocc", os.path.join(s.work, "mask.png"),
         "--error-map", os.path.join(s.work, "mask.png")],
        ["quad"] + [os.path.join(views, v) for v in ("a.png", "b.png", "c.png", "d.png")] +
        ["-o", os.path.join(s.work, "q.pfm"), "--ndisp", "8", "--window", "5",
         "--certainty", os.path.join(views, "c.png")],
        ["distort", distort_scene, elsewhere],
        ["distort", distort_scene, os.path.join(distort_scene, "distorted")],
        ["cloud", s.f("gt.png"), s.f("left.png"), "-o", os.path.join(s.work, "calib.ply"),
         "--calib", os.path.join(s.work, "calib.ply")],
    ]
    for argv in cases:
        before = tree(s.work)
        status, stdout, stderr = run([s.stereo] + argv)
        after = tree(s.work)
        what = " ".join(os.path.relpath(w, s.work) if w.startswith(s.work) else w for w in argv)
        if status != 2 or stdout or not one_error_line(stderr):
            fail("%s: exit %s, stdout %r, stderr %r (expected exit 2, one error line)"
                 % (what, status, stdout[:100], stderr[:300]))
        elif before != after:
            changed = sorted(set(before.items()) ^ set(after.items()))
            fail("%s: files changed: %s" % (what, changed[:4]))
        else:
            print("ok: %s: %s" % (what, stderr.decode().strip()))


def case_staging(s):
    # The video used to be staged as ".NAME.partial.avi": a link planted there redirected it.
    out = os.path.join(s.work, "planted")
    os.makedirs(out)
    victim = os.path.join(s.work, "victim.bin")
    with open(victim, "wb") as f:
        f.write(b"someone else's file")
    os.symlink(victim, os.path.join(out, ".o.avi.partial.avi"))
    template, output = s.writers(False)["avi"]
    status, _, stderr = run(s.argv(template, out), stdout=subprocess.DEVNULL)
    if status != 0:
        fail("avoid --overlay o.avi: exit %s (%r)" % (status, stderr))
    with open(victim, "rb") as f:
        if f.read() != b"someone else's file":
            fail("the write followed the planted link: the victim changed")
    if os.path.islink(os.path.join(out, output)) or not os.path.isfile(os.path.join(out, output)):
        fail("o.avi is not a regular file of its own")
    print("ok: a link at the old staging name of the video is not followed")
    if not s.rtl:
        return 0
    # While a trace is written, the only thing beside the destination is a private folder (mode
    # 0700, made by mkdtemp): FST's writer opens its files (the trace and ".hier") by name, and
    # a folder only this user can write into is what keeps those names from being planted.
    template, output = s.writers(True)["fst"]
    out = os.path.join(s.work, "trace")
    os.makedirs(out)
    process = subprocess.Popen(s.argv(template, out), stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    seen = set()
    while process.poll() is None:
        for name in hidden(out):
            path = os.path.join(out, name)
            try:
                mode = os.lstat(path).st_mode
            except FileNotFoundError:
                continue
            seen.add((name, stat.S_ISDIR(mode), stat.S_IMODE(mode)))
        time.sleep(0.001)
    if process.returncode != 0:
        fail("cosim --trace: exit %s" % process.returncode)
    if not seen:
        fail("no staging entry was ever seen beside the trace: the test did not test")
    for name, folder, mode in sorted(seen):
        if not folder or mode != 0o700:
            fail("staged beside the destination: %s (%s, mode %o)"
                 % (name, "folder" if folder else "file", mode))
    print("ok: the trace was staged in %s" % sorted(seen))
    return 0


def case_sweep(s):
    # A SIGKILL cannot be caught: the temporary stays, until the next run writes there.
    template, output = s.writers(True)["ply"]
    out = os.path.join(s.work, "sweep")
    os.makedirs(out)
    put_previous(out, output)
    left_behind = []
    for _ in range(20):
        process = subprocess.Popen(s.argv(template, out), stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        while process.poll() is None and not writing(out):
            time.sleep(0.0005)
        process.kill()
        process.wait()
        left_behind = hidden(out)
        if left_behind:
            break
    if not left_behind:
        print("skip: no run could be killed while writing")
        return SKIP
    print("SIGKILL left %s" % left_behind)
    # ".c.ply.PID-TAG.XXXXXX": the same name with a live PID (this test's) must stay.
    name = left_behind[0]
    dot = name.rfind(".")
    dash = name.rfind("-")
    pid_at = name.rfind(".", 0, dash) + 1
    live = name[:pid_at] + str(os.getpid()) + name[dash:dot] + ".Zzzzzz"
    with open(os.path.join(out, live), "w") as f:
        f.write("a live process's temporary")
    status, _, stderr = run(s.argv(template, out), stdout=subprocess.DEVNULL)
    if status != 0:
        fail("the next run: exit %s (%r)" % (status, stderr))
    remaining = hidden(out)
    if remaining != [live]:
        fail("after the next run: %s, expected only %s" % (remaining, live))
    else:
        print("ok: the next run removed %s and kept %s" % (left_behind, live))
    return 0


def main():
    if len(sys.argv) != 8:
        print(__doc__)
        return 2
    setup = Setup(sys.argv[1:])
    result = globals()["case_" + setup.case](setup)
    if result == SKIP:
        return SKIP
    if FAILURES:
        print("%d failure(s)" % len(FAILURES))
        return 1
    print("all ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
