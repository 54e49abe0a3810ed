#!/usr/bin/env python3
"""Doxygen INPUT_FILTER for the public headers (docs/api/Doxyfile.in): their comments are plain
`//` prose, so this turns them into Doxygen comments on the fly, line for line (warnings keep
their line numbers), and leaves the headers as they are.

  - the comment that opens a file (before any code) becomes the file's description (@file);
  - a run of `//` lines before a declaration becomes `///`, its documentation;
  - a `//` comment after a declaration (`;` or `,` before it) becomes `///<`, the member's
    documentation;
  - rulers (`// ----`) stay plain comments. Doxygen ignores comments inside function bodies.

usage: comment_filter.py HEADER   (the filtered text on standard output)
"""
import os
import re
import sys

TRAILING = re.compile(r'^(?P<code>[^"\']*?\S)(?P<gap>\s+)//(?!/)\s?(?P<text>.*)$')
LEADING = re.compile(r"^(?P<indent>\s*)//(?![/!<])\s?(?P<text>.*)$")


def prose(text):
    """Comment text as Doxygen reads it literally: `<name>` is not an HTML tag, `0 ..` no list end."""
    return text.replace("<", "\\<").replace(">", "\\>").replace("..", "\\.\\.")


def filter_lines(lines, name):
    out = []
    seen_code = False
    in_file_comment = False
    for number, line in enumerate(lines):
        body = line.rstrip("\n")
        leading = LEADING.match(body)
        if leading and not seen_code:
            text = prose(leading.group("text"))
            if not in_file_comment:
                in_file_comment = True
                out.append(f"/** @file {name} {text}")
            else:
                out.append(f"    {text}")
            continue
        if in_file_comment:
            out[-1] += " */"
            in_file_comment = False
        if body.strip():
            seen_code = True
        if leading:
            text = prose(leading.group("text"))
            if re.fullmatch(r"[-=*# ]*", text) or text.startswith("NOLINT"):
                out.append(body)  # rulers and lint markers are not documentation
            else:
                out.append(f"{leading.group('indent')}/// {text}")
            continue
        trailing = TRAILING.match(body)
        if trailing and trailing.group("code").rstrip().endswith((";", ",")) \
                and "namespace" not in trailing.group("code"):
            out.append(f"{trailing.group('code')}{trailing.group('gap')}///< {prose(trailing.group('text'))}")
            continue
        out.append(body)
    if in_file_comment:
        out[-1] += " */"
    return out


def main():
    with open(sys.argv[1], encoding="utf-8") as header:
        lines = header.readlines()
    sys.stdout.write("\n".join(filter_lines(lines, os.path.basename(sys.argv[1]))) + "\n")


if __name__ == "__main__":
    main()
