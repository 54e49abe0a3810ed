#!/usr/bin/env python3
"""Runs the fenced code blocks of README.md and docs/*.md (ctest docs.snippets and
docs.snippets_long; the rules are in docs/testing.md, "Documentation snippets").

Every block needs a language tag. Blocks tagged sh, bash, console or python run; `text` blocks
(formulas, diagrams, synopses, output listings) are not code and do not run. Any other language
(cpp, cmake, systemverilog, ...) and every block that cannot run here carries a marker on the
line before its fence:

  <!-- snippet: skip (REASON) -->          not run; the reason is printed
  <!-- snippet: long (REASON) -->          run only with --long (ctest label docs)
  <!-- snippet: data (REASON) -->          needs the shared data (STEREO_DATA_DIR); skipped,
                                           with the reason, when that folder is absent
  <!-- snippet: long data (REASON) -->     both
  <!-- snippet: excerpt PATH (REASON) -->  each line of the block occurs in the repository file
                                           PATH (code shown from a file that a test builds)

Shell blocks run with bash -e -o pipefail in a scratch folder that looks like the repository
(its top-level entries linked, docs/ copied, build/ a folder of links to the build's entries, so
that what a block writes stays in the scratch folder), with build/app and build/experiments first in PATH,
A set to the folder of Debian opencv-doc's Aloe pair, ../shared/data the shared data (when
present), HOME the scratch folder, and the files
LEFT, RIGHT, LEFT.png, RIGHT.png, L.png, R.png, left.png and right.png holding the Aloe pair at
half size (641x555). A console block runs its `$ ` lines (with their continuation lines) and
ignores the output lines. Python blocks run with the build's module on PYTHONPATH. The blocks of
one markdown file run in order in one scratch folder, so a block may read what an earlier one
wrote.

usage: run_snippets.py --source DIR --build DIR [--long] [--list] [FILE.md ...]
exit 0 when every block that ran passed and every block is tagged or marked.
"""
import argparse
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from pathlib import Path

RUN_LANGUAGES = {"sh", "bash", "console", "python"}
MARKER = re.compile(r"^<!--\s*snippet:\s*(?P<kinds>[a-z ]+?)\s*(?P<path>[\w./-]+\.\w+)?\s*"
                    r"\((?P<reason>[^)]*(?:\([^)]*\)[^)]*)*)\)\s*-->\s*$")
FENCE = re.compile(r"^(?P<indent>\s*)(?P<fence>```+|~~~+)\s*(?P<info>[^`\s]*)\s*(?P<rest>.*)$")
KINDS = {"skip", "long", "data", "excerpt"}
# Markdown files whose blocks are not checked yet, with the reason (printed every run).
NOT_CHECKED: dict[str, str] = {}


class Block:
    def __init__(self, path, line, language, body, marker):
        self.path, self.line, self.language, self.body, self.marker = path, line, language, body, marker

    @property
    def where(self):
        return f"{self.path}:{self.line}"


def parse(source, relative):
    """The fenced blocks of one markdown file, and the problems of their tags and markers."""
    blocks, problems = [], []
    lines = (source / relative).read_text(encoding="utf-8").split("\n")
    i = 0
    while i < len(lines):
        match = FENCE.match(lines[i])
        if not match:
            i += 1
            continue
        fence, language = match.group("fence"), match.group("info").lower()
        start = i
        i += 1
        body = []
        while i < len(lines) and not lines[i].strip().startswith(fence):
            body.append(lines[i][len(match.group("indent")):] if lines[i].startswith(match.group("indent")) else lines[i])
            i += 1
        i += 1
        previous = lines[start - 1].strip() if start > 0 else ""
        marker = None
        if previous.startswith("<!--") and "snippet:" in previous:
            parsed = MARKER.match(previous)
            if not parsed:
                problems.append(f"{relative}:{start + 1}: malformed marker {previous!r}: "
                                "<!-- snippet: KIND [PATH] (REASON) -->")
            else:
                kinds = set(parsed.group("kinds").split())
                unknown = kinds - KINDS
                if unknown or not parsed.group("reason").strip():
                    problems.append(f"{relative}:{start + 1}: marker {previous!r}: kinds are "
                                    f"{sorted(KINDS)}, and a reason in parentheses is required")
                elif ("excerpt" in kinds) != bool(parsed.group("path")):
                    problems.append(f"{relative}:{start + 1}: `excerpt` takes a repository path, alone")
                else:
                    marker = {"kinds": kinds, "path": parsed.group("path"),
                              "reason": parsed.group("reason").strip()}
        block = Block(relative, start + 1, language, body, marker)
        if not language:
            problems.append(f"{block.where}: no language tag (sh, console, python, text, ...)")
        elif language not in RUN_LANGUAGES and language != "text" and marker is None:
            problems.append(f"{block.where}: a {language} block needs a marker: "
                            "<!-- snippet: excerpt PATH (...) --> or <!-- snippet: skip (...) -->")
        blocks.append(block)
    return blocks, problems


def png(path, width, height, rgb):
    """An 8-bit RGB PNG from row-major bytes (standard library only)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\0" + rgb[y * width * 3:(y + 1) * width * 3] for y in range(height))
    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(rows, 6)) + chunk(b"IEND", b""))


def half_size_pair(build, aloe, folder):
    """LEFT, RIGHT and their aliases: the Aloe pair at half size, through the built module."""
    script = (
        "import sys, stereo\n"
        "for name in ('L', 'R'):\n"
        "    a = stereo.load_image(sys.argv[1] + '/aloe' + name + '.jpg', downscale=2)\n"
        "    sys.stdout.buffer.write(b'%d %d\\n' % (a.shape[1], a.shape[0]) + a.tobytes())\n")
    out = subprocess.run(["/usr/bin/python3", "-c", script, str(aloe)], check=True, capture_output=True,
                         env=dict(os.environ, PYTHONPATH=str(build / "python"))).stdout
    for side, names in (("L", ("LEFT", "LEFT.png", "L.png", "left.png")),
                        ("R", ("RIGHT", "RIGHT.png", "R.png", "right.png"))):
        header, _, rest = out.partition(b"\n")
        width, height = map(int, header.split())
        size = width * height * 3
        png(folder / names[0], width, height, rest[:size])
        out = rest[size:]
        for alias in names[1:]:
            shutil.copyfile(folder / names[0], folder / alias)


def scratch_folder(root, source, build, aloe, name):
    folder = root / name
    folder.mkdir()
    for entry in source.iterdir():
        if entry.name not in ("build", ".git", "docs"):
            (folder / entry.name).symlink_to(entry)
    shutil.copytree(source / "docs", folder / "docs", symlinks=True)  # blocks may write into docs/
    (folder / "build").mkdir()
    for entry in build.iterdir():
        (folder / "build" / entry.name).symlink_to(entry)
    half_size_pair(build, aloe, folder)
    return folder


def console_commands(body):
    commands, continuing = [], False
    for line in body:
        if line.startswith("$ ") or continuing:
            commands.append(line[2:] if line.startswith("$ ") and not continuing else line)
            continuing = line.rstrip().endswith("\\")
    return commands


def run_block(block, folder, env, timeout):
    if block.language == "python":
        script = folder / f"snippet_{block.line}.py"
        script.write_text("\n".join(block.body) + "\n", encoding="utf-8")
        command = ["/usr/bin/python3", str(script)]
    else:
        body = console_commands(block.body) if block.language == "console" else block.body
        command = ["bash", "-e", "-o", "pipefail", "-c", "\n".join(body) + "\n"]
    started = time.monotonic()
    result = subprocess.run(command, cwd=folder, env=env, stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
    return result.returncode, result.stdout.decode(errors="replace"), time.monotonic() - started


def code(line):
    """A line without its trailing comment (`//` or ` #`) and surrounding blanks."""
    return re.sub(r"\s+(//|#)\s.*$", "", line).strip()


def check_excerpt(block, source):
    target = source / block.marker["path"]
    if not target.is_file():
        return f"{block.marker['path']} does not exist"
    lines = {code(line) for line in target.read_text(encoding="utf-8").split("\n")}
    missing = [line for line in block.body if code(line) and code(line) not in lines]
    return f"not in {block.marker['path']}: {missing[0].strip()!r}" if missing else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", type=Path, required=True)
    parser.add_argument("--build", type=Path, required=True)
    parser.add_argument("--long", action="store_true", help="run the blocks marked long (only those)")
    parser.add_argument("--list", action="store_true", help="check tags and markers, run nothing")
    parser.add_argument("--timeout", type=float, default=1800, help="seconds per block")
    parser.add_argument("files", nargs="*", help="markdown files relative to --source")
    args = parser.parse_args()
    source, build = args.source.resolve(), args.build.resolve()
    aloe = Path(os.environ.get("STEREO_ALOE_DIR", "/usr/share/doc/opencv-doc/examples/data"))
    data = Path(os.environ.get("STEREO_DATA_DIR", source.parent / "shared" / "data"))
    files = args.files or ["README.md"] + sorted(str(p.relative_to(source)) for p in (source / "docs").glob("*.md"))

    problems, blocks = [], []
    for relative in files:
        if relative in NOT_CHECKED:
            print(f"NOT CHECKED {relative}: {NOT_CHECKED[relative]}")
            continue
        found, trouble = parse(source, relative)
        blocks += found
        problems += trouble
    for problem in problems:
        print(f"ERROR {problem}")

    counts = {"run": 0, "passed": 0, "failed": 0, "skipped": 0, "text": 0, "excerpt": 0, "other-label": 0}
    reasons = {}
    failures = []
    root = Path(tempfile.mkdtemp(prefix="snippets."))
    if data.is_dir():  # ../shared/data, as beside the repository
        (root / "shared").mkdir()
        (root / "shared" / "data").symlink_to(data.resolve())
    folders = {}
    env = dict(os.environ, A=str(aloe), PYTHONPATH=str(build / "python"), PYTHONDONTWRITEBYTECODE="1",
               STEREO_DATA_DIR=str(data), STEREO_ALOE_DIR=str(aloe))
    try:
        for block in blocks:
            if not block.language:
                continue  # an error above
            marker = block.marker or {"kinds": set(), "path": None, "reason": ""}
            kinds = marker["kinds"]
            if block.language == "text" and not kinds:
                counts["text"] += 1
                continue
            if "excerpt" in kinds:
                counts["excerpt"] += 1
                error = None if args.list else check_excerpt(block, source)
                if error:
                    failures.append(f"{block.where}: excerpt {error}")
                    print(f"FAIL {block.where} excerpt: {error}")
                continue
            if "skip" in kinds or block.language not in RUN_LANGUAGES:
                counts["skipped"] += 1
                reasons.setdefault(marker["reason"] or block.language, []).append(block.where)
                print(f"SKIP {block.where} ({marker['reason']})")
                continue
            if ("long" in kinds) != args.long:
                counts["other-label"] += 1
                continue
            if "data" in kinds and not data.is_dir():
                counts["skipped"] += 1
                reason = f"no shared data at {data}"
                reasons.setdefault(reason, []).append(block.where)
                print(f"SKIP {block.where} ({reason}: {marker['reason']})")
                continue
            if args.list:
                print(f"WOULD RUN {block.where} {block.language}")
                continue
            if block.path not in folders:
                folders[block.path] = scratch_folder(root, source, build, aloe, re.sub(r"\W", "_", block.path))
            folder = folders[block.path]
            env_block = dict(env, HOME=str(folder), PATH=f"{build / 'app'}:{build / 'experiments'}:{os.environ['PATH']}")
            counts["run"] += 1
            try:
                code, output, seconds = run_block(block, folder, env_block, args.timeout)
            except subprocess.TimeoutExpired:
                code, output, seconds = -1, f"timed out after {args.timeout} s", args.timeout
            if code == 0:
                counts["passed"] += 1
                print(f"PASS {block.where} {block.language} {seconds:.1f} s")
            else:
                counts["failed"] += 1
                failures.append(block.where)
                print(f"FAIL {block.where} {block.language} exit {code} after {seconds:.1f} s; output:")
                print("    " + "\n    ".join(output.rstrip().split("\n")[-30:]))
    finally:
        shutil.rmtree(root, ignore_errors=True)

    print()
    print("skipped, by reason:")
    for reason, where in sorted(reasons.items()):
        print(f"  {len(where):3d}  {reason}: {', '.join(where)}")
    label = "long" if args.long else "default"
    print(f"snippets ({label} set): {len(blocks)} blocks in {len(files)} files: {counts['run']} run "
          f"({counts['passed']} passed, {counts['failed']} failed), {counts['skipped']} skipped, "
          f"{counts['text']} text, {counts['excerpt']} excerpts checked, "
          f"{counts['other-label']} in the {'default' if args.long else 'long'} set; "
          f"{len(problems)} untagged or unmarked")
    return 1 if problems or failures else 0


if __name__ == "__main__":
    sys.exit(main())
